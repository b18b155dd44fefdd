#include "game/gltf/gltf_animation.h"

#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <memory>
#include <string>

#include "game/gltf/gltf_accessors.h"
#include "game/scene/json_fields.h"

namespace rtrt {

void ReadGltfAnimation(GltfDocument& doc, const std::vector<int32_t>& nodeSlot, GltfAsset& asset) {
    const tinygltf::Model& model = doc.Model();
    if (model.animations.empty()) return;
    if (model.animations.size() > 1)
        doc.Warn("animations", "animations: " + std::to_string(model.animations.size()) +
                                   " animations; rtrt plays the first");
    const tinygltf::Animation& anim = model.animations[0];
    std::map<int32_t, physics::KeyframeClip> clips;
    float duration = 0.0f;
    for (size_t c = 0; c < anim.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = anim.channels[c];
        const std::string at = JsonIndexed("animations[0].channels", c);
        if (ch.target_path == "weights") {
            doc.Warn("morph", at + ".target.path: weights (morph targets) are not "
                                   "supported; meshes keep their base shape");
            continue;
        }
        if (ch.target_path != "translation" && ch.target_path != "rotation" &&
            ch.target_path != "scale")
            doc.Fail(at + ".target.path", "unknown path \"" + ch.target_path + "\"");
        if (ch.target_node < 0 || size_t(ch.target_node) >= model.nodes.size())
            doc.Fail(at + ".target.node",
                     "node " + std::to_string(ch.target_node) + " out of range");
        if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
            doc.Fail(at + ".sampler", "sampler " + std::to_string(ch.sampler) + " out of range");
        const int32_t slot = nodeSlot[size_t(ch.target_node)];
        if (slot < 0) continue;  // a node outside the scene shown
        const tinygltf::AnimationSampler& s = anim.samplers[size_t(ch.sampler)];
        const std::string samplerAt = JsonIndexed("animations[0].samplers", size_t(ch.sampler));
        physics::Interpolation mode = physics::Interpolation::kLinear;
        const bool cubic = s.interpolation == "CUBICSPLINE";
        if (s.interpolation == "STEP")
            mode = physics::Interpolation::kStep;
        else if (cubic)
            doc.Warn("cubic", samplerAt +
                                  ".interpolation: CUBICSPLINE is played as LINEAR "
                                  "between its values (tangents ignored)");
        else if (s.interpolation != "LINEAR" && !s.interpolation.empty())
            doc.Fail(samplerAt + ".interpolation", "unknown \"" + s.interpolation + "\"");
        std::vector<float> times;
        try {
            for (const glm::vec<1, float>& t :
                 ReadGltfFloats<1>(doc, s.input, samplerAt + ".input", TINYGLTF_TYPE_SCALAR))
                times.push_back(t.x);
        } catch (const GltfUnsupported& u) {
            doc.Warn("unsupported:" + u.what, at + ": " + u.what + "; the channel is skipped");
            continue;
        }
        const size_t perKey = cubic ? 3 : 1;
        auto values = [&](auto read) {
            auto all = read();
            if (all.size() != times.size() * perKey)
                doc.Fail(samplerAt + ".output", std::to_string(all.size()) + " values for " +
                                                    std::to_string(times.size()) + " key times");
            decltype(all) keys;
            for (size_t k = 0; k < times.size(); ++k) keys.push_back(all[k * perKey + perKey / 2]);
            return keys;
        };
        physics::KeyframeClip& clip = clips[slot];
        try {
            if (ch.target_path == "rotation") {
                const auto v = values([&] {
                    return ReadGltfFloats<4>(doc, s.output, samplerAt + ".output",
                                             TINYGLTF_TYPE_VEC4);
                });
                clip.rotation.times = times;
                for (const glm::vec4& q : v) {
                    const glm::dquat r(q.w, q.x, q.y, q.z);
                    if (!(glm::length(r) > 0.0))
                        doc.Fail(samplerAt + ".output", "a rotation quaternion is zero");
                    clip.rotation.values.push_back(glm::quat(glm::normalize(r)));
                }
                clip.rotation.interpolation =
                    mode == physics::Interpolation::kStep ? mode : physics::Interpolation::kSlerp;
            } else {
                physics::Vec3Track& track =
                    ch.target_path == "translation" ? clip.translation : clip.scale;
                track.times = times;
                track.values = values([&] {
                    return ReadGltfFloats<3>(doc, s.output, samplerAt + ".output",
                                             TINYGLTF_TYPE_VEC3);
                });
                track.interpolation = mode;
            }
        } catch (const GltfUnsupported& u) {
            doc.Warn("unsupported:" + u.what, at + ": " + u.what + "; the channel is skipped");
            continue;
        }
        if (!times.empty()) duration = std::max(duration, times.back());
        clip.wrap = physics::WrapMode::kLoop;
        if (const std::string problem = physics::ValidateClip(clip); !problem.empty())
            doc.Fail(samplerAt + ".input", problem);
    }
    // Every clip loops over the whole animation: a track that ends early holds its last
    // value until the animation's end.
    for (auto& [slot, clip] : clips) {
        auto pad = [&](auto& track) {
            if (!track.Empty() && track.times.back() < duration) {
                track.times.push_back(duration);
                track.values.push_back(track.values.back());
            }
        };
        pad(clip.translation);
        pad(clip.rotation);
        pad(clip.scale);
        if (clip.Duration() <= 0.0f) continue;  // one key at time 0: a constant pose
        asset.nodes[size_t(slot)].clip = std::make_shared<const physics::KeyframeClip>(clip);
        asset.summary.animatedNodes++;
    }
    asset.summary.animationSeconds = duration;
}

}  // namespace rtrt
