#include "game/gltf/gltf_animation.h"

#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <type_traits>
#include <utility>

#include "game/gltf/gltf_accessors.h"
#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

// A sampler's output split by key. Each key holds `width` elements (a weights key one per morph
// target); a CUBICSPLINE key holds its in-tangents, then its values, then its out-tangents
// (glTF 2.0, "Animations": "the elements of the output accessor are grouped").
template <typename T>
struct KeyedOutput {
    std::vector<T> values, inTangents, outTangents;
};

template <typename T>
KeyedOutput<T> SplitOutput(const GltfDocument& doc, std::vector<T> all, size_t keys, size_t width,
                           bool cubic, const std::string& field) {
    const size_t perKey = width * (cubic ? 3 : 1);
    if (all.size() != keys * perKey)
        doc.Fail(field,
                 std::to_string(all.size()) + " values for " + std::to_string(keys) + " key times" +
                     (width > 1 ? " of " + std::to_string(width) + " weights" : "") +
                     (cubic ? " (CUBICSPLINE: in-tangent, value, out-tangent per key)" : ""));
    KeyedOutput<T> out;
    if (!cubic) {
        out.values = std::move(all);
        return out;
    }
    for (size_t k = 0; k < keys; ++k)
        for (size_t i = 0; i < width; ++i) {
            out.inTangents.push_back(all[k * perKey + i]);
            out.values.push_back(all[k * perKey + width + i]);
            out.outTangents.push_back(all[k * perKey + 2 * width + i]);
        }
    return out;
}

// The morph targets of a node's mesh (every primitive of a mesh has the same number).
size_t MorphTargetCount(const tinygltf::Model& model, int node) {
    const int mesh = model.nodes[size_t(node)].mesh;
    if (mesh < 0 || size_t(mesh) >= model.meshes.size()) return 0;
    const std::vector<tinygltf::Primitive>& prims = model.meshes[size_t(mesh)].primitives;
    return prims.empty() ? 0 : prims[0].targets.size();
}

// Holds a track's last value until the animation's end; a cubic track's last segment is then
// flat (its old last out-tangent, which shaped nothing, now leaves a key: it becomes zero).
template <typename Values>
void PadTo(float duration, std::vector<float>& times, Values& values, Values& in, Values& out,
           bool cubic, size_t width) {
    if (times.empty() || !(times.back() < duration)) return;
    times.push_back(duration);
    const size_t last = values.size() - width;
    for (size_t i = 0; i < width; ++i) values.push_back(values[last + i]);
    if (!cubic) return;
    using T = typename Values::value_type;
    T zero;
    if constexpr (std::is_same_v<T, glm::quat>)
        zero = glm::quat(0.0f, 0.0f, 0.0f, 0.0f);
    else
        zero = T(0.0f);
    for (size_t i = 0; i < width; ++i) {
        out[last + i] = zero;
        in.push_back(zero);
        out.push_back(zero);
    }
}

class ChannelReader {
  public:
    ChannelReader(GltfDocument& doc, const tinygltf::Animation& anim)
        : doc_(doc), model_(doc.Model()), anim_(anim) {}

    // Reads channel c into its node's clip, or skips it with a warning.
    void Read(size_t c, physics::KeyframeClip& clip, float& duration) {
        const tinygltf::AnimationChannel& ch = anim_.channels[c];
        const std::string at = doc_.FirstAnimationChannel(c);
        const tinygltf::AnimationSampler& s = anim_.samplers[size_t(ch.sampler)];
        const std::string samplerAt = JsonIndexed("animations[0].samplers", size_t(ch.sampler));
        physics::Interpolation mode = physics::Interpolation::kLinear;
        if (s.interpolation == "STEP")
            mode = physics::Interpolation::kStep;
        else if (s.interpolation == "CUBICSPLINE")
            mode = physics::Interpolation::kCubicSpline;
        else if (s.interpolation != "LINEAR" && !s.interpolation.empty())
            doc_.Fail(samplerAt + ".interpolation", "unknown \"" + s.interpolation + "\"");
        const bool cubic = mode == physics::Interpolation::kCubicSpline;
        const std::string output = samplerAt + ".output";
        try {
            std::vector<float> times;
            for (const glm::vec<1, float>& t :
                 ReadGltfFloats<1>(doc_, s.input, samplerAt + ".input", TINYGLTF_TYPE_SCALAR))
                times.push_back(t.x);
            if (ch.target_path == "weights") {
                const size_t targets = MorphTargetCount(model_, ch.target_node);
                if (targets == 0) {
                    doc_.Warn("weights-without-targets",
                              at + ".target.node: a weights channel on a node without morph "
                                   "targets; the channel is skipped");
                    return;
                }
                std::vector<float> all;
                for (const glm::vec<1, float>& w :
                     ReadGltfFloats<1>(doc_, s.output, output, TINYGLTF_TYPE_SCALAR))
                    all.push_back(w.x);
                auto split =
                    SplitOutput(doc_, std::move(all), times.size(), targets, cubic, output);
                physics::WeightsTrack& track = clip.weights;
                track.count = uint32_t(targets);
                track.interpolation = mode;
                track.values = std::move(split.values);
                track.inTangents = std::move(split.inTangents);
                track.outTangents = std::move(split.outTangents);
                track.times = std::move(times);
            } else if (ch.target_path == "rotation") {
                auto split =
                    SplitOutput(doc_, ReadGltfFloats<4>(doc_, s.output, output, TINYGLTF_TYPE_VEC4),
                                times.size(), 1, cubic, output);
                physics::QuatTrack& track = clip.rotation;
                track.values.clear();
                for (const glm::vec4& q : split.values) {
                    const glm::dquat r(q.w, q.x, q.y, q.z);
                    if (!(glm::length(r) > 0.0)) doc_.Fail(output, "a rotation quaternion is zero");
                    track.values.push_back(glm::quat(glm::normalize(r)));
                }
                // Tangents stay as written: the spline is normalised after (SampleTrack).
                auto quats = [](const std::vector<glm::vec4>& v) {
                    std::vector<glm::quat> q;
                    for (const glm::vec4& x : v) q.push_back(glm::quat(x.w, x.x, x.y, x.z));
                    return q;
                };
                track.inTangents = quats(split.inTangents);
                track.outTangents = quats(split.outTangents);
                // glTF's LINEAR rotation is a slerp.
                track.interpolation =
                    mode == physics::Interpolation::kLinear ? physics::Interpolation::kSlerp : mode;
                track.times = std::move(times);
            } else {
                physics::Vec3Track& track =
                    ch.target_path == "translation" ? clip.translation : clip.scale;
                auto split =
                    SplitOutput(doc_, ReadGltfFloats<3>(doc_, s.output, output, TINYGLTF_TYPE_VEC3),
                                times.size(), 1, cubic, output);
                track.values = std::move(split.values);
                track.inTangents = std::move(split.inTangents);
                track.outTangents = std::move(split.outTangents);
                track.interpolation = mode;
                track.times = std::move(times);
            }
            if (const std::string problem = physics::ValidateClip(clip); !problem.empty())
                doc_.Fail(samplerAt + ".input", problem);
            const std::vector<float>& t = ch.target_path == "weights"       ? clip.weights.times
                                          : ch.target_path == "rotation"    ? clip.rotation.times
                                          : ch.target_path == "translation" ? clip.translation.times
                                                                            : clip.scale.times;
            if (!t.empty()) duration = std::max(duration, t.back());
        } catch (const GltfUnsupported& u) {
            doc_.Warn("unsupported:" + u.what, at + ": " + u.what + "; the channel is skipped");
        }
    }

  private:
    GltfDocument& doc_;
    const tinygltf::Model& model_;
    const tinygltf::Animation& anim_;
};

void Pad(physics::KeyframeClip& clip, float duration) {
    auto pad = [&](auto& track) {
        const bool cubic = track.interpolation == physics::Interpolation::kCubicSpline;
        PadTo(duration, track.times, track.values, track.inTangents, track.outTangents, cubic, 1);
    };
    pad(clip.translation);
    pad(clip.rotation);
    pad(clip.scale);
    physics::WeightsTrack& w = clip.weights;
    PadTo(duration, w.times, w.values, w.inTangents, w.outTangents,
          w.interpolation == physics::Interpolation::kCubicSpline, w.count);
}

}  // namespace

void ReadGltfAnimation(GltfDocument& doc, const std::vector<int32_t>& nodeSlot, GltfAsset& asset) {
    const tinygltf::Model& model = doc.Model();
    if (model.animations.empty()) return;
    if (model.animations.size() > 1)
        doc.Warn("animations", "animations: " + std::to_string(model.animations.size()) +
                                   " animations; rtrt plays the first");
    const tinygltf::Animation& anim = model.animations[0];
    std::map<int32_t, physics::KeyframeClip> clips;
    ChannelReader reader(doc, anim);
    float duration = 0.0f;
    std::set<std::pair<int, std::string>> targets;
    for (size_t c = 0; c < anim.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = anim.channels[c];
        const std::string at = doc.FirstAnimationChannel(c);
        if (ch.target_path != "translation" && ch.target_path != "rotation" &&
            ch.target_path != "scale" && ch.target_path != "weights")
            doc.Fail(at + ".target.path", "unknown path \"" + ch.target_path + "\"");
        if (ch.target_node < 0 || size_t(ch.target_node) >= model.nodes.size())
            doc.Fail(at + ".target.node",
                     "node " + std::to_string(ch.target_node) + " out of range");
        if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
            doc.Fail(at + ".sampler", "sampler " + std::to_string(ch.sampler) + " out of range");
        // One animation drives each node's path once (glTF 2.0, 3.11).
        if (!targets.insert({ch.target_node, ch.target_path}).second)
            doc.Fail(at + ".target", "node " + std::to_string(ch.target_node) + "'s " +
                                         ch.target_path + " is animated by an earlier channel too");
        const int32_t slot = nodeSlot[size_t(ch.target_node)];
        if (slot < 0) continue;  // a node outside the scene shown
        physics::KeyframeClip& clip = clips[slot];
        clip.wrap = physics::WrapMode::kLoop;
        reader.Read(c, clip, duration);
    }
    // Every clip loops over the whole animation: a track that ends early holds its last
    // value until the animation's end.
    for (auto& [slot, clip] : clips) {
        Pad(clip, duration);
        if (clip.Duration() <= 0.0f) {
            // Keys at time 0 only (how exporters write a pose): the node's own transform and
            // weights become that pose. Dropped, the node had stayed at its rest pose.
            GltfNode& node = asset.nodes[size_t(slot)];
            physics::SampleClip(clip, 0.0, node.local);
            const physics::WeightsTrack& w = clip.weights;
            if (!w.Empty() && w.count == node.morphWeights.size())
                node.morphWeights.assign(w.values.begin(), w.values.begin() + long(w.count));
            continue;
        }
        asset.nodes[size_t(slot)].clip = std::make_shared<const physics::KeyframeClip>(clip);
        asset.summary.animatedNodes++;
    }
    asset.summary.animationSeconds = duration;
}

}  // namespace rtrt
