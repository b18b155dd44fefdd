#include "game/gltf/gltf_nodes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <utility>

#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

// The nodes of the scene shown: the default scene's roots, else the first scene's, else
// every node without a parent.
std::vector<int> Roots(GltfDocument& doc, const std::vector<int>& parentOf) {
    const tinygltf::Model& model = doc.Model();
    std::vector<int> roots;
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (model.defaultScene >= int(model.scenes.size()))
        doc.Fail("scene", "scene " + std::to_string(model.defaultScene) + " out of range");
    if (!model.scenes.empty()) {
        const std::vector<int>& nodes = model.scenes[size_t(sceneIndex)].nodes;
        for (size_t i = 0; i < nodes.size(); ++i) {
            const std::string field =
                JsonIndexed(JsonIndexed("scenes", size_t(sceneIndex)) + ".nodes", i);
            if (nodes[i] < 0 || size_t(nodes[i]) >= model.nodes.size())
                doc.Fail(field, "node " + std::to_string(nodes[i]) + " out of range");
            roots.push_back(nodes[i]);
        }
        // Each listed node is shown once: the specification wants them unique, and a list that
        // repeats a root would show its whole tree again for every repeat.
        std::vector<char> seen(model.nodes.size(), 0);
        size_t unique = 0;
        for (size_t i = 0; i < roots.size(); ++i) {
            if (seen[size_t(roots[i])] != 0) {
                doc.Warn("scene-repeat",
                         JsonIndexed(JsonIndexed("scenes", size_t(sceneIndex)) + ".nodes", i) +
                             ": node " + std::to_string(roots[i]) +
                             " is listed again; it is shown once");
                continue;
            }
            seen[size_t(roots[i])] = 1;
            roots[unique++] = roots[i];
        }
        roots.resize(unique);
        // The specification wants roots here, but files list children too and common engines
        // load them: a child whose tree is shown anyway is shown there, once; one whose tree is
        // not is shown as a root of its own (its ancestors' transforms are not applied).
        std::vector<char> listed(model.nodes.size(), 0);
        for (const int node : roots) listed[size_t(node)] = 1;
        // Per node, whether some ancestor is listed (-1: not known yet); each node is settled
        // once, so that long chains under many listed children cost linear time.
        std::vector<int8_t> listedAbove(model.nodes.size(), -1);
        std::vector<int> path;
        const auto hasListedAncestor = [&](int node) {
            path.clear();
            int up = parentOf[size_t(node)];
            int8_t found = 0;
            for (; up >= 0; up = parentOf[size_t(up)]) {
                if (listed[size_t(up)] != 0) {
                    found = 1;
                    break;
                }
                if (listedAbove[size_t(up)] >= 0) {
                    found = listedAbove[size_t(up)];
                    break;
                }
                path.push_back(up);
            }
            for (const int p : path) listedAbove[size_t(p)] = found;
            return found == 1;
        };
        std::vector<int> kept;
        for (size_t i = 0; i < roots.size(); ++i) {
            const int node = roots[i];
            if (parentOf[node] < 0) {
                kept.push_back(node);
                continue;
            }
            // Some ancestor is listed: the node is reached from it.
            const bool shownAbove = hasListedAncestor(node);
            const std::string field =
                JsonIndexed(JsonIndexed("scenes", size_t(sceneIndex)) + ".nodes", i);
            doc.Warn("scene-child", field + ": node " + std::to_string(node) +
                                        " has a parent (node " + std::to_string(parentOf[node]) +
                                        "); " +
                                        (shownAbove ? "it is shown under it"
                                                    : "it is shown as a root, without its "
                                                      "ancestors' transforms"));
            if (!shownAbove) kept.push_back(node);
        }
        roots = std::move(kept);
        if (model.scenes.size() > 1)
            doc.Warn("scenes", "scenes: " + std::to_string(model.scenes.size()) +
                                   " scenes; rtrt shows scene " + std::to_string(sceneIndex));
    } else {
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (parentOf[i] < 0) roots.push_back(int(i));
    }
    return roots;
}

// The rotation of a basis with zero-length axes (LENGTHS): the others normalised, the missing
// ones made perpendicular to them, right-handed.
glm::quat CompletedRotation(const glm::mat3& basis, const vec3& lengths) {
    glm::mat3 axes(1.0f);
    int kept = 0, only = 0;
    for (int c = 0; c < 3; ++c)
        if (lengths[c] > 0.0f) {
            axes[c] = basis[c] / lengths[c];
            ++kept;
            only = c;
        }
    if (kept == 0) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    if (kept == 1) {
        const vec3 a = axes[only];
        const vec3 helper = std::fabs(a.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
        axes[(only + 1) % 3] = glm::normalize(glm::cross(a, helper));
        axes[(only + 2) % 3] = glm::cross(a, axes[(only + 1) % 3]);
    } else {
        for (int c = 0; c < 3; ++c)
            if (!(lengths[c] > 0.0f))
                axes[c] = glm::normalize(glm::cross(axes[(c + 1) % 3], axes[(c + 2) % 3]));
    }
    return glm::normalize(glm::quat_cast(axes));
}

// A node matrix as translation, rotation and scale (rtrt's LocalTransform); a shear is lost,
// with a warning.
physics::LocalTransform Decompose(GltfDocument& doc, const std::vector<double>& m,
                                  const std::string& field) {
    glm::mat4 matrix;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) matrix[c][r] = float(m[size_t(c) * 4 + size_t(r)]);
    physics::LocalTransform t;
    t.translation = vec3(matrix[3]);
    glm::mat3 basis(matrix);
    t.scale = vec3(glm::length(basis[0]), glm::length(basis[1]), glm::length(basis[2]));
    if (!(t.scale.x > 0.0f && t.scale.y > 0.0f && t.scale.z > 0.0f)) {
        // A zero scale (what hides a node, as "scale": [0, 0, 0] does): the rotation is made
        // of the axes left, completed to a right-handed basis.
        t.rotation = CompletedRotation(basis, t.scale);
        return t;
    }
    if (glm::determinant(basis) < 0.0f) t.scale.x = -t.scale.x;
    for (int c = 0; c < 3; ++c) basis[c] /= t.scale[c];
    const float shear = std::fabs(glm::dot(basis[0], basis[1])) +
                        std::fabs(glm::dot(basis[1], basis[2])) +
                        std::fabs(glm::dot(basis[0], basis[2]));
    if (shear > 1e-3f || m[3] != 0.0 || m[7] != 0.0 || m[11] != 0.0 || m[15] != 1.0)
        doc.Warn("shear", field +
                              ": shear or projection is not supported; the node keeps its "
                              "translation, rotation and scale");
    t.rotation = glm::normalize(glm::quat_cast(basis));
    return t;
}

physics::LocalTransform NodeTransform(GltfDocument& doc, size_t index) {
    const tinygltf::Model& model = doc.Model();
    const tinygltf::Node& node = model.nodes[index];
    const std::string at = JsonIndexed("nodes", index);
    auto finite = [&](const std::vector<double>& values, const char* field, size_t size) {
        if (!values.empty() && values.size() != size)
            doc.Fail(at + "." + field, "expected " + std::to_string(size) + " numbers");
        for (double v : values)
            if (!FiniteFloat(v))
                doc.Fail(at + "." + field, "a value is NaN or infinite (or beyond float range)");
    };
    finite(node.translation, "translation", 3);
    finite(node.rotation, "rotation", 4);
    finite(node.scale, "scale", 3);
    finite(node.matrix, "matrix", 16);
    physics::LocalTransform t;
    if (!node.matrix.empty()) return Decompose(doc, node.matrix, at + ".matrix");
    if (!node.translation.empty())
        t.translation = vec3(node.translation[0], node.translation[1], node.translation[2]);
    if (!node.rotation.empty()) {
        // Normalised in double: components near float's range would overflow the length.
        const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        if (!(glm::length(q) > 0.0)) doc.Fail(at + ".rotation", "the quaternion is zero");
        t.rotation = glm::quat(glm::normalize(q));
    }
    if (!node.scale.empty()) t.scale = vec3(node.scale[0], node.scale[1], node.scale[2]);
    return t;
}

// The weights a node's mesh starts with: the node's own, else the mesh's, else zeros; none
// for a mesh without morph targets.
std::vector<float> MorphWeights(const GltfDocument& doc, size_t index, const std::string& at) {
    const tinygltf::Model& model = doc.Model();
    const tinygltf::Node& node = model.nodes[index];
    const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
    const size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
    if (!node.weights.empty() && node.weights.size() != targets)
        doc.Fail(at + ".weights", std::to_string(node.weights.size()) + " weights for " +
                                      std::to_string(targets) + " morph targets of its mesh");
    const std::vector<double>& given = node.weights.empty() ? mesh.weights : node.weights;
    std::vector<float> weights(targets, 0.0f);
    for (size_t t = 0; t < given.size() && t < targets; ++t) {
        if (!FiniteFloat(given[t]))
            doc.Fail(at + ".weights", "a weight is NaN or infinite (or beyond float range)");
        weights[t] = float(given[t]);
    }
    return weights;
}

}  // namespace

// Every node has at most one parent and no node is its own ancestor: the hierarchy is a
// forest, so that entities can be created parents first.
std::vector<int> CheckGltfNodeGraph(const GltfDocument& doc) {
    const tinygltf::Model& model = doc.Model();
    const size_t n = model.nodes.size();
    std::vector<int> parentOf(n, -1);
    for (size_t i = 0; i < n; ++i) {
        const std::vector<int>& children = model.nodes[i].children;
        for (size_t c = 0; c < children.size(); ++c) {
            const int child = children[c];
            const std::string field = JsonIndexed(JsonIndexed("nodes", i) + ".children", c);
            if (child < 0 || size_t(child) >= n)
                doc.Fail(field, "node " + std::to_string(child) + " out of range (" +
                                    std::to_string(n) + " nodes)");
            if (size_t(child) == i)
                doc.Fail(field, "node " + std::to_string(i) + " is its own child");
            if (parentOf[child] >= 0)
                doc.Fail(field, "node " + std::to_string(child) + " has two parents (nodes " +
                                    std::to_string(parentOf[child]) + " and " + std::to_string(i) +
                                    ")");
            parentOf[child] = int(i);
        }
    }
    // Each node has at most one parent, so walking up from every node finds any cycle; a node
    // whose walk already ended at a root is not walked again (linear time for long chains).
    std::vector<uint8_t> state(n, 0);  // 0: not visited, 1: on the current walk, 2: reaches a root
    for (size_t i = 0; i < n; ++i) {
        int at = int(i);
        while (at >= 0 && state[size_t(at)] == 0) {
            state[size_t(at)] = 1;
            at = parentOf[size_t(at)];
        }
        if (at >= 0 && state[size_t(at)] == 1)
            doc.Fail(JsonIndexed("nodes", size_t(at)) + ".children",
                     "node " + std::to_string(at) + " is its own ancestor (a cycle)");
        for (at = int(i); at >= 0 && state[size_t(at)] == 1; at = parentOf[size_t(at)])
            state[size_t(at)] = 2;
    }
    return parentOf;
}

void ReadGltfCamerasAndLights(GltfDocument& doc, GltfAsset& asset) {
    const tinygltf::Model& model = doc.Model();
    for (size_t i = 0; i < model.cameras.size(); ++i) {
        const tinygltf::Camera& c = model.cameras[i];
        GltfCamera camera;
        if (c.type == "perspective") {
            // glTF allows any angle above 0 (and below pi); a telephoto's is under a degree.
            const double pi = 3.14159265358979323846;
            const double fov = c.perspective.yfov * 180.0 / pi;
            if (!(c.perspective.yfov > 0.0 && c.perspective.yfov < pi))
                doc.Fail(JsonIndexed("cameras", i) + ".perspective.yfov",
                         "must be above 0 and below pi (radians), got " +
                             std::to_string(c.perspective.yfov));
            // Float ray directions resolve about 1e-7 of the view's width: below 1e-3 radians an
            // image thousands of pixels high would repeat rows.
            if (c.perspective.yfov < 1e-3)
                doc.Fail(JsonIndexed("cameras", i) + ".perspective.yfov",
                         "is below 1e-3 radians (0.06 degrees), narrower than float rays resolve, "
                         "got " +
                             std::to_string(c.perspective.yfov));
            camera.fovYDegrees = float(fov);
            if (FiniteFloat(c.perspective.aspectRatio) && c.perspective.aspectRatio > 0.0)
                camera.aspect = float(c.perspective.aspectRatio);
        } else {
            doc.Warn("orthographic", JsonIndexed("cameras", i) + ": " + c.type +
                                         " cameras are not supported; skipped");
            camera.fovYDegrees = 0.0f;  // marks it skipped
        }
        asset.cameras.push_back(camera);
    }
    for (size_t i = 0; i < model.lights.size(); ++i) {
        const tinygltf::Light& l = model.lights[i];
        const std::string at = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
        GltfLight light;
        if (l.type == "directional") {
            light.type = LightType::kDirectional;
        } else if (l.type == "point") {
            light.type = LightType::kPoint;
        } else if (l.type == "spot") {
            light.type = LightType::kSpot;
            const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
            if (!FiniteFloat(outer) || outer <= 0.0 || outer > M_PI / 2)
                doc.Fail(at + ".spot.outerConeAngle", "must be above 0 and at most pi/2");
            if (!FiniteFloat(inner) || inner < 0.0 || inner >= outer)
                doc.Fail(at + ".spot.innerConeAngle",
                         "must be at least 0 and below outerConeAngle");
            light.innerCone = float(inner);
            light.outerCone = float(outer);
        } else {
            doc.Fail(at + ".type", "unknown light type \"" + l.type + "\"");
        }
        if (!l.color.empty() && l.color.size() != 3) doc.Fail(at + ".color", "expected 3 numbers");
        for (double c : l.color)
            if (!FiniteFloat(c) || c < 0.0 || c > 1e6) doc.Fail(at + ".color", "must be 0 to 1e6");
        if (!FiniteFloat(l.intensity) || l.intensity < 0.0 || l.intensity > 1e7)
            doc.Fail(at + ".intensity", "must be 0 to 1e7");
        if (!FiniteFloat(l.range) || l.range < 0.0)
            doc.Fail(at + ".range", "must be positive (or 0: unlimited)");
        const vec3 color =
            l.color.size() == 3 ? vec3(l.color[0], l.color[1], l.color[2]) : vec3(1.0f);
        // Physical units: lux for directional lights, candela for point and spot lights, which
        // fall off with the square of the distance, smoothly to nothing at range; rtrt's light
        // colours are those over pi (light.h).
        light.color = color * float(l.intensity / M_PI);
        light.range = light.type == LightType::kDirectional ? 0.0f : float(l.range);
        asset.lights.push_back(light);
    }
}

std::vector<int32_t> ReadGltfNodes(GltfDocument& doc, const std::vector<int>& parentOf,
                                   GltfMeshes& meshes, GltfAsset& asset) {
    const tinygltf::Model& model = doc.Model();
    const std::vector<int> roots = Roots(doc, parentOf);
    std::vector<std::pair<int, int32_t>> stack;  // (node, index of its parent in asset nodes)
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1});
    std::vector<int32_t> nodeSlot(model.nodes.size(), -1);
    while (!stack.empty()) {
        const auto [index, parent] = stack.back();
        stack.pop_back();
        const tinygltf::Node& node = model.nodes[size_t(index)];
        GltfNode out;
        out.parent = parent;
        out.source = uint32_t(index);
        out.local = NodeTransform(doc, size_t(index));
        const std::string at = JsonIndexed("nodes", size_t(index));
        if (node.skin < -1 || (node.skin >= 0 && size_t(node.skin) >= model.skins.size()))
            doc.Fail(at + ".skin", "skin " + std::to_string(node.skin) + " out of range");
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model.meshes.size())
                doc.Fail(at + ".mesh", "mesh " + std::to_string(node.mesh) + " out of range");
            out.primitives = meshes.Primitives(size_t(node.mesh), node.skin);
            out.skin = node.skin;
            out.morphWeights = MorphWeights(doc, size_t(index), at);
        } else if (node.mesh < -1) {
            doc.Fail(at + ".mesh", "mesh " + std::to_string(node.mesh) + " out of range");
        }
        if (node.camera >= 0) {
            if (size_t(node.camera) >= model.cameras.size())
                doc.Fail(at + ".camera", "camera " + std::to_string(node.camera) + " out of range");
            if (asset.cameras[size_t(node.camera)].fovYDegrees > 0.0f) out.camera = node.camera;
        }
        auto light = node.extensions.find("KHR_lights_punctual");
        if (light != node.extensions.end()) {
            const tinygltf::Value& v = light->second.Get("light");
            if (!v.IsInt() || v.GetNumberAsInt() < 0 ||
                size_t(v.GetNumberAsInt()) >= asset.lights.size())
                doc.Fail(at + ".extensions.KHR_lights_punctual.light",
                         "expected the index of a light (there are " +
                             std::to_string(asset.lights.size()) + ")");
            out.light = v.GetNumberAsInt();
        }
        nodeSlot[size_t(index)] = int32_t(asset.nodes.size());
        asset.nodes.push_back(std::move(out));
        const int32_t self = nodeSlot[size_t(index)];
        for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
            stack.push_back({*c, self});
    }
    asset.summary.nodes = uint32_t(asset.nodes.size());
    asset.summary.cameras = 0;
    asset.summary.lights = 0;
    for (const GltfNode& n : asset.nodes) {
        asset.summary.cameras += n.camera >= 0;
        asset.summary.lights += n.light >= 0;
    }
    return nodeSlot;
}

}  // namespace rtrt
