#include "game/gltf/gltf_import.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include "engine/core/error.h"
#include "game/gltf/gltf_image_loader.h"
#include "game/gltf/gltf_precheck.h"
#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

bool Finite(double v) { return std::isfinite(v) && std::fabs(v) <= 3.0e38; }

// tinygltf's messages can span lines and start with "Error: "; the CLI prints one line.
std::string OneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    if (text.rfind("Error: ", 0) == 0) text = text.substr(7);
    return text.empty() ? "tinygltf could not load the file" : text;
}

// An accessor whose every element lies inside its buffer, read as floats (normalised integers
// scaled as the spec says) or as unsigned indices.
struct AccessorView {
    const uint8_t* data = nullptr;
    size_t stride = 0, count = 0;
    int componentType = 0, components = 0;
    bool normalized = false;

    float Component(size_t element, int c) const {
        const uint8_t* p = data + element * stride;
        switch (componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                float v;
                std::memcpy(&v, p + 4 * c, 4);
                return v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                return normalized ? p[c] / 255.0f : float(p[c]);
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                const float v = float(int8_t(p[c]));
                return normalized ? std::max(v / 127.0f, -1.0f) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t v;
                std::memcpy(&v, p + 2 * c, 2);
                return normalized ? v / 65535.0f : float(v);
            }
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                int16_t v;
                std::memcpy(&v, p + 2 * c, 2);
                return normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
            }
            default: {
                uint32_t v;
                std::memcpy(&v, p + 4 * c, 4);
                return float(v);
            }
        }
    }
    uint32_t Index(size_t element) const {
        const uint8_t* p = data + element * stride;
        if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return p[0];
        if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
};

// Thrown for content rtrt skips with a warning (a sparse accessor): the caller drops what used it.
struct Unsupported {
    std::string what;
};

class Importer {
  public:
    Importer(std::string path, LoadedScene& out) : file_(std::move(path)), out_(out) {}

    GltfAsset Run() {
        Load();
        CheckExtensions();
        asset_.summary.file = file_;
        asset_.summary.meshes = uint32_t(model_.meshes.size());
        asset_.summary.textures = uint32_t(model_.textures.size());
        asset_.summary.materials = uint32_t(model_.materials.size());
        asset_.summary.animations = uint32_t(model_.animations.size());
        CheckNodeGraph();
        ReadCamerasAndLights();
        ReadNodes();
        ReadAnimation();
        return std::move(asset_);
    }

  private:
    [[noreturn]] void Fail(const std::string& field, const std::string& reason) const {
        throw InputError(file_, field, reason);
    }
    // One warning per kind of thing rtrt does not support, however often the file uses it.
    void Warn(const std::string& kind, const std::string& text) {
        if (!warned_.insert(kind).second) return;
        std::fprintf(stderr, "rtrt: warning: %s: %s\n", file_.c_str(), text.c_str());
    }

    void Load() {
        const GltfFileBytes checked = ReadCheckedGltf(file_);
        const std::string& bytes = checked.bytes;
        const bool binary = checked.binary;
        const std::string dir = fs::path(file_).parent_path().string();
        tinygltf::TinyGLTF loader;
        GltfImageFailure imageFailure;
        InstallGltfImageLoader(loader, &imageFailure);
        std::string err, warn;
        const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
        const bool ok =
            binary ? loader.LoadBinaryFromMemory(&model_, &err, &warn, data, unsigned(bytes.size()),
                                                 dir.empty() ? "." : dir)
                   : loader.LoadASCIIFromString(&model_, &err, &warn, bytes.data(),
                                                unsigned(bytes.size()), dir.empty() ? "." : dir);
        if (imageFailure.index >= 0)
            Fail(JsonIndexed("images", size_t(imageFailure.index)), OneLine(imageFailure.reason));
        if (!ok || !err.empty()) Fail("", OneLine(err));
    }

    void CheckExtensions() {
        static const std::set<std::string> kUsed = {"KHR_lights_punctual",
                                                    "KHR_materials_transmission",
                                                    "KHR_materials_ior",
                                                    "KHR_materials_specular",
                                                    "KHR_materials_emissive_strength",
                                                    "KHR_materials_pbrSpecularGlossiness"};
        for (const std::string& ext : model_.extensionsRequired)
            if (!kUsed.count(ext))
                Warn("ext:" + ext, "extensionsRequired: " + ext +
                                       " is not supported; what needs it is ignored or skipped");
        if (!model_.skins.empty())
            Warn("skins", "skins: skinning is not supported; skinned meshes keep their bind pose");
    }

    // Every node has at most one parent and no node is its own ancestor: the hierarchy is a
    // forest, so that entities can be created parents first.
    void CheckNodeGraph() {
        const size_t n = model_.nodes.size();
        parentOf_.assign(n, -1);
        for (size_t i = 0; i < n; ++i) {
            const std::vector<int>& children = model_.nodes[i].children;
            for (size_t c = 0; c < children.size(); ++c) {
                const int child = children[c];
                const std::string field = JsonIndexed(JsonIndexed("nodes", i) + ".children", c);
                if (child < 0 || size_t(child) >= n)
                    Fail(field, "node " + std::to_string(child) + " out of range (" +
                                    std::to_string(n) + " nodes)");
                if (size_t(child) == i)
                    Fail(field, "node " + std::to_string(i) + " is its own child");
                if (parentOf_[child] >= 0)
                    Fail(field, "node " + std::to_string(child) + " has two parents (nodes " +
                                    std::to_string(parentOf_[child]) + " and " + std::to_string(i) +
                                    ")");
                parentOf_[child] = int(i);
            }
        }
        for (size_t i = 0; i < n; ++i) {
            int at = int(i);
            for (size_t steps = 0; at >= 0; ++steps) {
                if (steps > n)
                    Fail(JsonIndexed("nodes", i) + ".children",
                         "node " + std::to_string(i) + " is its own ancestor (a cycle)");
                at = parentOf_[at];
            }
        }
    }

    // The nodes of the scene shown: the default scene's roots, else the first scene's, else
    // every node without a parent.
    std::vector<int> Roots() {
        std::vector<int> roots;
        const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (model_.defaultScene >= int(model_.scenes.size()))
            Fail("scene", "scene " + std::to_string(model_.defaultScene) + " out of range");
        if (!model_.scenes.empty()) {
            const std::vector<int>& nodes = model_.scenes[size_t(sceneIndex)].nodes;
            for (size_t i = 0; i < nodes.size(); ++i) {
                const std::string field =
                    JsonIndexed(JsonIndexed("scenes", size_t(sceneIndex)) + ".nodes", i);
                if (nodes[i] < 0 || size_t(nodes[i]) >= model_.nodes.size())
                    Fail(field, "node " + std::to_string(nodes[i]) + " out of range");
                if (parentOf_[nodes[i]] >= 0)
                    Fail(field, "node " + std::to_string(nodes[i]) +
                                    " is not a root (its parent is node " +
                                    std::to_string(parentOf_[nodes[i]]) + ")");
                roots.push_back(nodes[i]);
            }
            if (model_.scenes.size() > 1)
                Warn("scenes", "scenes: " + std::to_string(model_.scenes.size()) +
                                   " scenes; rtrt shows scene " + std::to_string(sceneIndex));
        } else {
            for (size_t i = 0; i < model_.nodes.size(); ++i)
                if (parentOf_[i] < 0) roots.push_back(int(i));
        }
        return roots;
    }

    physics::LocalTransform NodeTransform(size_t index) {
        const tinygltf::Node& node = model_.nodes[index];
        const std::string at = JsonIndexed("nodes", index);
        auto finite = [&](const std::vector<double>& values, const char* field, size_t size) {
            if (!values.empty() && values.size() != size)
                Fail(at + "." + field, "expected " + std::to_string(size) + " numbers");
            for (double v : values)
                if (!Finite(v))
                    Fail(at + "." + field, "a value is NaN or infinite (or beyond float range)");
        };
        finite(node.translation, "translation", 3);
        finite(node.rotation, "rotation", 4);
        finite(node.scale, "scale", 3);
        finite(node.matrix, "matrix", 16);
        physics::LocalTransform t;
        if (!node.matrix.empty()) return Decompose(node.matrix, at + ".matrix");
        if (!node.translation.empty())
            t.translation = vec3(node.translation[0], node.translation[1], node.translation[2]);
        if (!node.rotation.empty()) {
            // Normalised in double: components near float's range would overflow the length.
            const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1],
                               node.rotation[2]);
            if (!(glm::length(q) > 0.0)) Fail(at + ".rotation", "the quaternion is zero");
            t.rotation = glm::quat(glm::normalize(q));
        }
        if (!node.scale.empty()) t.scale = vec3(node.scale[0], node.scale[1], node.scale[2]);
        return t;
    }

    // A node matrix as translation, rotation and scale (rtrt's LocalTransform); a shear is lost,
    // with a warning.
    physics::LocalTransform Decompose(const std::vector<double>& m, const std::string& field) {
        glm::mat4 matrix;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) matrix[c][r] = float(m[size_t(c) * 4 + size_t(r)]);
        physics::LocalTransform t;
        t.translation = vec3(matrix[3]);
        glm::mat3 basis(matrix);
        t.scale = vec3(glm::length(basis[0]), glm::length(basis[1]), glm::length(basis[2]));
        if (!(t.scale.x > 0.0f && t.scale.y > 0.0f && t.scale.z > 0.0f))
            Fail(field, "the matrix is singular (a zero scale)");
        if (glm::determinant(basis) < 0.0f) t.scale.x = -t.scale.x;
        for (int c = 0; c < 3; ++c) basis[c] /= t.scale[c];
        const float shear = std::fabs(glm::dot(basis[0], basis[1])) +
                            std::fabs(glm::dot(basis[1], basis[2])) +
                            std::fabs(glm::dot(basis[0], basis[2]));
        if (shear > 1e-3f || m[3] != 0.0 || m[7] != 0.0 || m[11] != 0.0 || m[15] != 1.0)
            Warn("shear", field +
                              ": shear or projection is not supported; the node keeps its "
                              "translation, rotation and scale");
        t.rotation = glm::normalize(glm::quat_cast(basis));
        return t;
    }

    void ReadCamerasAndLights() {
        for (size_t i = 0; i < model_.cameras.size(); ++i) {
            const tinygltf::Camera& c = model_.cameras[i];
            GltfCamera camera;
            if (c.type == "perspective") {
                const double fov = c.perspective.yfov * 180.0 / 3.14159265358979323846;
                if (!(fov >= 1.0 && fov <= 179.0))
                    Fail(JsonIndexed("cameras", i) + ".perspective.yfov",
                         "must be between 1 and 179 degrees (in radians), got " +
                             std::to_string(c.perspective.yfov));
                camera.fovYDegrees = float(fov);
                if (Finite(c.perspective.aspectRatio) && c.perspective.aspectRatio > 0.0)
                    camera.aspect = float(c.perspective.aspectRatio);
            } else {
                Warn("orthographic", JsonIndexed("cameras", i) + ": " + c.type +
                                         " cameras are not supported; skipped");
                camera.fovYDegrees = 0.0f;  // marks it skipped
            }
            asset_.cameras.push_back(camera);
        }
        for (size_t i = 0; i < model_.lights.size(); ++i) {
            const tinygltf::Light& l = model_.lights[i];
            const std::string at =
                "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
            GltfLight light;
            if (l.type == "directional") {
                light.type = LightType::kDirectional;
            } else if (l.type == "point" || l.type == "spot") {
                light.type = LightType::kPoint;
                if (l.type == "spot")
                    Warn("spot", at + ": spot lights are rendered as point lights (no cone)");
            } else {
                Fail(at + ".type", "unknown light type \"" + l.type + "\"");
            }
            if (!l.color.empty() && l.color.size() != 3) Fail(at + ".color", "expected 3 numbers");
            for (double c : l.color)
                if (!Finite(c) || c < 0.0 || c > 1e6) Fail(at + ".color", "must be 0 to 1e6");
            if (!Finite(l.intensity) || l.intensity < 0.0 || l.intensity > 1e6)
                Fail(at + ".intensity", "must be 0 to 1e6");
            const vec3 color =
                l.color.size() == 3 ? vec3(l.color[0], l.color[1], l.color[2]) : vec3(1.0f);
            // rtrt lights do not fall off with distance: colour x intensity as it is.
            light.color = color * float(l.intensity);
            asset_.lights.push_back(light);
        }
    }

    void ReadNodes() {
        const std::vector<int> roots = Roots();
        std::vector<std::pair<int, int32_t>> stack;  // (node, index of its parent in asset nodes)
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1});
        nodeSlot_.assign(model_.nodes.size(), -1);
        while (!stack.empty()) {
            const auto [index, parent] = stack.back();
            stack.pop_back();
            const tinygltf::Node& node = model_.nodes[size_t(index)];
            GltfNode out;
            out.parent = parent;
            out.source = uint32_t(index);
            out.local = NodeTransform(size_t(index));
            const std::string at = JsonIndexed("nodes", size_t(index));
            if (node.mesh >= 0) {
                if (size_t(node.mesh) >= model_.meshes.size())
                    Fail(at + ".mesh", "mesh " + std::to_string(node.mesh) + " out of range");
                out.primitives = MeshPrimitives(size_t(node.mesh));
            } else if (node.mesh < -1) {
                Fail(at + ".mesh", "mesh " + std::to_string(node.mesh) + " out of range");
            }
            if (node.camera >= 0) {
                if (size_t(node.camera) >= model_.cameras.size())
                    Fail(at + ".camera", "camera " + std::to_string(node.camera) + " out of range");
                if (asset_.cameras[size_t(node.camera)].fovYDegrees > 0.0f)
                    out.camera = node.camera;
            }
            auto light = node.extensions.find("KHR_lights_punctual");
            if (light != node.extensions.end()) {
                const tinygltf::Value& v = light->second.Get("light");
                if (!v.IsInt() || v.GetNumberAsInt() < 0 ||
                    size_t(v.GetNumberAsInt()) >= asset_.lights.size())
                    Fail(at + ".extensions.KHR_lights_punctual.light",
                         "expected the index of a light (there are " +
                             std::to_string(asset_.lights.size()) + ")");
                out.light = v.GetNumberAsInt();
            }
            if (node.skin >= 0)
                Warn("skins", at + ".skin: skinning is not supported; skinned meshes keep "
                                   "their bind pose");
            if (!node.weights.empty())
                Warn("morph", at + ".weights: morph targets are not supported; meshes keep "
                                   "their base shape");
            nodeSlot_[size_t(index)] = int32_t(asset_.nodes.size());
            asset_.nodes.push_back(std::move(out));
            const int32_t self = nodeSlot_[size_t(index)];
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
                stack.push_back({*c, self});
        }
        asset_.summary.nodes = uint32_t(asset_.nodes.size());
        asset_.summary.cameras = 0;
        asset_.summary.lights = 0;
        for (const GltfNode& n : asset_.nodes) {
            asset_.summary.cameras += n.camera >= 0;
            asset_.summary.lights += n.light >= 0;
        }
    }

    // The BLAS and material of each triangle primitive of a mesh, built on first use.
    std::vector<std::pair<uint32_t, uint32_t>> MeshPrimitives(size_t mesh) {
        auto found = meshPrimitives_.find(mesh);
        if (found != meshPrimitives_.end()) return found->second;
        std::vector<std::pair<uint32_t, uint32_t>> result;
        const tinygltf::Mesh& m = model_.meshes[mesh];
        for (size_t p = 0; p < m.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = m.primitives[p];
            const std::string at = JsonIndexed(JsonIndexed("meshes", mesh) + ".primitives", p);
            if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
                Warn("mode", at + ".mode: mode " + std::to_string(prim.mode) +
                                 " (points, lines, strips or fans) is not supported; such "
                                 "primitives are skipped");
                continue;
            }
            if (!prim.targets.empty())
                Warn("morph", at + ".targets: morph targets are not supported; meshes keep "
                                   "their base shape");
            TriangleMesh triangles;
            try {
                triangles = ReadPrimitive(prim, at);
            } catch (const Unsupported& u) {
                Warn("unsupported:" + u.what, at + ": " + u.what + "; the primitive is skipped");
                continue;
            }
            if (triangles.indices.empty()) continue;
            asset_.summary.primitives++;
            asset_.summary.vertices += uint32_t(triangles.positions.size());
            asset_.summary.triangles += uint32_t(triangles.indices.size());
            const uint32_t blas =
                out_.scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(triangles)));
            out_.modelNames.push_back(fs::path(file_).filename().string() + " " + at +
                                      (m.name.empty() ? "" : " (" + m.name + ")"));
            result.push_back({blas, MaterialId(prim.material, at + ".material")});
        }
        meshPrimitives_[mesh] = result;
        return result;
    }

    AccessorView Accessor(int index, const std::string& field, std::initializer_list<int> types) {
        if (index < 0 || size_t(index) >= model_.accessors.size())
            Fail(field, "accessor " + std::to_string(index) + " out of range (" +
                            std::to_string(model_.accessors.size()) + " accessors)");
        const tinygltf::Accessor& a = model_.accessors[size_t(index)];
        const std::string at = JsonIndexed("accessors", size_t(index));
        if (a.sparse.isSparse) throw Unsupported{"sparse accessors are not supported"};
        if (std::find(types.begin(), types.end(), a.type) == types.end())
            Fail(at + ".type", "wrong element type for " + field);
        const int componentBytes = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        if (componentBytes <= 0 || componentBytes == 8 || components <= 0)
            Fail(at + ".componentType",
                 "unknown component type " + std::to_string(a.componentType));
        if (a.count == 0) Fail(at + ".count", "must be at least 1");
        if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size())
            Fail(at + ".bufferView",
                 "buffer view " + std::to_string(a.bufferView) + " out of range");
        const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
        const std::string viewAt = JsonIndexed("bufferViews", size_t(a.bufferView));
        if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
            Fail(viewAt + ".buffer", "buffer " + std::to_string(view.buffer) + " out of range");
        const std::vector<unsigned char>& buffer = model_.buffers[size_t(view.buffer)].data;
        if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
            Fail(viewAt + ".byteLength", "bytes " + std::to_string(view.byteOffset) + " + " +
                                             std::to_string(view.byteLength) +
                                             " lie outside buffer " + std::to_string(view.buffer) +
                                             " of " + std::to_string(buffer.size()) + " bytes");
        const uint64_t element = uint64_t(componentBytes) * uint64_t(components);
        const uint64_t stride = view.byteStride ? view.byteStride : element;
        if (stride < element || stride > 252)
            Fail(viewAt + ".byteStride", "stride " + std::to_string(stride) +
                                             " does not hold an element of " +
                                             std::to_string(element) + " bytes (or exceeds 252)");
        // count - 1 strides plus one element from byteOffset must fit in the view; count is
        // bounded by the view first, so nothing overflows.
        const uint64_t length = view.byteLength;
        if (a.byteOffset > length || element > length - a.byteOffset ||
            uint64_t(a.count - 1) > (length - a.byteOffset - element) / stride)
            Fail(at + ".count", std::to_string(a.count) + " elements from byte " +
                                    std::to_string(a.byteOffset) + " do not fit in buffer view " +
                                    std::to_string(a.bufferView) + " of " + std::to_string(length) +
                                    " bytes");
        AccessorView v;
        v.data = buffer.data() + view.byteOffset + a.byteOffset;
        v.stride = size_t(stride);
        v.count = a.count;
        v.componentType = a.componentType;
        v.components = components;
        v.normalized = a.normalized;
        return v;
    }

    template <int N>
    std::vector<glm::vec<N, float>> ReadFloats(int index, const std::string& field, int type) {
        const AccessorView a = Accessor(index, field, {type});
        std::vector<glm::vec<N, float>> values(a.count);
        for (size_t i = 0; i < a.count; ++i)
            for (int c = 0; c < N; ++c) {
                const float v = a.Component(i, c);
                if (!Finite(v))
                    Fail(field, "accessor " + std::to_string(index) + ", element " +
                                    std::to_string(i) + ": NaN or infinite");
                values[i][c] = v;
            }
        return values;
    }

    TriangleMesh ReadPrimitive(const tinygltf::Primitive& prim, const std::string& at) {
        TriangleMesh mesh;
        auto attribute = [&](const char* name) {
            auto it = prim.attributes.find(name);
            return it == prim.attributes.end() ? -1 : it->second;
        };
        const int position = attribute("POSITION");
        if (position < 0) throw Unsupported{"a primitive without POSITION (compressed?)"};
        mesh.positions = ReadFloats<3>(position, at + ".attributes.POSITION", TINYGLTF_TYPE_VEC3);
        const size_t vertices = mesh.positions.size();
        if (const int normal = attribute("NORMAL"); normal >= 0) {
            mesh.normals = ReadFloats<3>(normal, at + ".attributes.NORMAL", TINYGLTF_TYPE_VEC3);
            if (mesh.normals.size() != vertices)
                Fail(at + ".attributes.NORMAL", "count differs from POSITION's");
            for (vec3& n : mesh.normals) {
                const float length = glm::length(n);
                n = length > 0.0f ? n / length : vec3(0, 1, 0);
            }
        }
        if (const int uv = attribute("TEXCOORD_0"); uv >= 0) {
            mesh.uvs = ReadFloats<2>(uv, at + ".attributes.TEXCOORD_0", TINYGLTF_TYPE_VEC2);
            if (mesh.uvs.size() != vertices)
                Fail(at + ".attributes.TEXCOORD_0", "count differs from POSITION's");
        }
        std::vector<uint32_t> indices;
        if (prim.indices >= 0) {
            const AccessorView a = Accessor(prim.indices, at + ".indices", {TINYGLTF_TYPE_SCALAR});
            if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                Fail(JsonIndexed("accessors", size_t(prim.indices)) + ".componentType",
                     "indices must be unsigned bytes, shorts or ints");
            indices.resize(a.count);
            for (size_t i = 0; i < a.count; ++i) {
                indices[i] = a.Index(i);
                if (indices[i] >= vertices)
                    Fail(at + ".indices", "index " + std::to_string(i) + " is " +
                                              std::to_string(indices[i]) + ", out of range (" +
                                              std::to_string(vertices) + " vertices)");
            }
        } else {
            indices.resize(vertices);
            for (size_t i = 0; i < vertices; ++i) indices[i] = uint32_t(i);
        }
        if (indices.size() % 3 != 0)
            Fail(prim.indices >= 0 ? at + ".indices" : at + ".attributes.POSITION",
                 std::to_string(indices.size()) + " indices do not make whole triangles");
        for (size_t i = 0; i < indices.size(); i += 3)
            mesh.indices.push_back({indices[i], indices[i + 1], indices[i + 2]});
        return mesh;
    }

    // glTF's metallic-roughness material as rtrt's Blinn-Phong (the README's table says why).
    uint32_t MaterialId(int index, const std::string& field) {
        if (index < 0) {
            if (defaultMaterial_ == UINT32_MAX) {
                defaultMaterial_ = out_.scene.AddMaterial(Material{});
                out_.materialNames.push_back("(default grey)");
            }
            return defaultMaterial_;
        }
        if (size_t(index) >= model_.materials.size())
            Fail(field, "material " + std::to_string(index) + " out of range");
        auto found = materialIds_.find(index);
        if (found != materialIds_.end()) return found->second;
        const tinygltf::Material& g = model_.materials[size_t(index)];
        const std::string at = JsonIndexed("materials", size_t(index));
        const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
        auto number = [&](double v, const std::string& name, double lo, double hi) {
            if (!(v >= lo && v <= hi))
                Fail(at + "." + name,
                     "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
            return float(v);
        };
        auto colour = [&](const std::vector<double>& v, const std::string& name, vec3 fallback) {
            if (v.empty()) return fallback;
            if (v.size() < 3) Fail(at + "." + name, "expected 3 or 4 numbers");
            return vec3(number(v[0], name, 0, 1e6), number(v[1], name, 0, 1e6),
                        number(v[2], name, 0, 1e6));
        };
        auto extension = [&](const char* name, const char* key, double fallback) {
            auto it = g.extensions.find(name);
            if (it == g.extensions.end() || !it->second.Has(key)) return fallback;
            const tinygltf::Value& v = it->second.Get(key);
            if (!v.IsNumber()) Fail(at + ".extensions." + name + "." + key, "expected a number");
            return v.GetNumberAsDouble();
        };
        const vec3 base =
            colour(pbr.baseColorFactor, "pbrMetallicRoughness.baseColorFactor", vec3(1));
        const float metallic =
            number(pbr.metallicFactor, "pbrMetallicRoughness.metallicFactor", 0, 1);
        const float roughness =
            number(pbr.roughnessFactor, "pbrMetallicRoughness.roughnessFactor", 0, 1);
        const float transmission =
            number(extension("KHR_materials_transmission", "transmissionFactor", 0.0),
                   "extensions.KHR_materials_transmission.transmissionFactor", 0, 1);
        const float ior = number(extension("KHR_materials_ior", "ior", 1.5),
                                 "extensions.KHR_materials_ior.ior", 1, 10);
        const float specularFactor =
            number(extension("KHR_materials_specular", "specularFactor", 1.0),
                   "extensions.KHR_materials_specular.specularFactor", 0, 1);
        vec3 specularColour(1.0f);
        if (auto it = g.extensions.find("KHR_materials_specular");
            it != g.extensions.end() && it->second.Has("specularColorFactor")) {
            const tinygltf::Value& v = it->second.Get("specularColorFactor");
            if (!v.IsArray() || v.ArrayLen() != 3)
                Fail(at + ".extensions.KHR_materials_specular.specularColorFactor",
                     "expected 3 numbers");
            for (int c = 0; c < 3; ++c) {
                if (!v.Get(c).IsNumber())
                    Fail(at + ".extensions.KHR_materials_specular.specularColorFactor",
                         "expected 3 numbers");
                specularColour[c] =
                    number(v.Get(c).GetNumberAsDouble(),
                           "extensions.KHR_materials_specular.specularColorFactor", 0, 1e6);
            }
        }
        const float strength =
            number(extension("KHR_materials_emissive_strength", "emissiveStrength", 1.0),
                   "extensions.KHR_materials_emissive_strength.emissiveStrength", 0, 1e6);
        const vec3 emissive = colour(g.emissiveFactor, "emissiveFactor", vec3(0.0f)) * strength;
        for (const auto& [name, value] : g.extensions)
            if (name != "KHR_materials_transmission" && name != "KHR_materials_ior" &&
                name != "KHR_materials_specular" && name != "KHR_materials_emissive_strength")
                Warn("material:" + name,
                     at + ".extensions." + name + ": not supported; the material ignores it");
        if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty())
            Warn("alpha",
                 at + ".alphaMode: " + g.alphaMode + " is not supported; surfaces are opaque");
        if (g.normalTexture.index >= 0 || g.occlusionTexture.index >= 0 ||
            g.emissiveTexture.index >= 0 || pbr.metallicRoughnessTexture.index >= 0)
            Warn("textures", at + ": only base colour textures are supported; normal, "
                                  "occlusion, emissive and metallic-roughness textures are "
                                  "ignored");

        // Dielectric reflectance at normal incidence from the index of refraction, scaled by
        // KHR_materials_specular; metals reflect their base colour (the glTF BRDF's F0).
        const float f0Dielectric = ((ior - 1.0f) / (ior + 1.0f)) * ((ior - 1.0f) / (ior + 1.0f));
        const vec3 f0 =
            glm::mix(glm::min(vec3(f0Dielectric) * specularColour, vec3(1.0f)) * specularFactor,
                     base, metallic);
        const float smooth = (1.0f - roughness) * (1.0f - roughness);
        Material m;
        m.diffuse = base * (1.0f - metallic) * (1.0f - transmission);
        m.ambient = 0.1f * base * (1.0f - metallic) + emissive;
        m.specular = f0;
        // Blinn-Phong exponent of the same highlight width as GGX of alpha = roughness^2
        // (Walter et al. 2007): n = 2 / alpha^2 - 2.
        const float alpha = std::max(roughness * roughness, 0.01f);
        m.shininess = std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 10000.0f);
        m.transmissivity = transmission * (1.0f - metallic);
        m.reflectivity =
            std::min(std::max(std::max(f0.x, f0.y), f0.z) * smooth, 1.0f - m.transmissivity);
        m.ior = ior;
        m.baseColorTexture = BaseColorTexture(pbr.baseColorTexture, at);
        const uint32_t id = out_.scene.AddMaterial(m);
        out_.materialNames.push_back(g.name.empty() ? fs::path(file_).filename().string() + " " + at
                                                    : g.name);
        materialIds_[index] = id;
        return id;
    }

    uint32_t BaseColorTexture(const tinygltf::TextureInfo& info, const std::string& materialAt) {
        if (info.index < 0) return kNoTexture;
        const std::string at = materialAt + ".pbrMetallicRoughness.baseColorTexture";
        if (size_t(info.index) >= model_.textures.size())
            Fail(at + ".index", "texture " + std::to_string(info.index) + " out of range");
        if (info.texCoord != 0) {
            Warn("texcoord", at + ".texCoord: only TEXCOORD_0 is supported; untextured");
            return kNoTexture;
        }
        if (info.extensions.count("KHR_texture_transform"))
            Warn("transform", at + ": KHR_texture_transform is ignored (textures are sampled "
                                   "at the primitive's own coordinates)");
        auto found = textureIds_.find(info.index);
        if (found != textureIds_.end()) return found->second;
        const tinygltf::Texture& t = model_.textures[size_t(info.index)];
        const std::string textureAt = JsonIndexed("textures", size_t(info.index));
        if (t.source < 0) {
            Warn("texture-source", textureAt +
                                       ": no image rtrt can read (an extension's "
                                       "format?); untextured");
            return textureIds_[info.index] = kNoTexture;
        }
        if (size_t(t.source) >= model_.images.size())
            Fail(textureAt + ".source", "image " + std::to_string(t.source) + " out of range");
        const tinygltf::Image& image = model_.images[size_t(t.source)];
        const std::string imageAt = JsonIndexed("images", size_t(t.source));
        const int channels = image.component, bytes = image.bits / 8;
        if (image.width <= 0 || image.height <= 0 || channels < 1 || channels > 4 ||
            (bytes != 1 && bytes != 2) ||
            image.image.size() !=
                size_t(image.width) * size_t(image.height) * size_t(channels) * size_t(bytes))
            Fail(imageAt, "the image is missing or could not be decoded");
        std::vector<uint32_t> rgba(size_t(image.width) * size_t(image.height));
        for (size_t p = 0; p < rgba.size(); ++p) {
            uint32_t c[4] = {0, 0, 0, 255};
            for (int k = 0; k < channels; ++k) {
                // 16-bit images keep their high byte, little-endian as stb and OIIO return them.
                c[k] = image.image[(p * size_t(channels) + size_t(k)) * size_t(bytes) +
                                   size_t(bytes - 1)];
            }
            if (channels <= 2) c[1] = c[2] = c[0];  // grey (and alpha)
            rgba[p] = c[0] | (c[1] << 8) | (c[2] << 16) | (c[3] << 24);
        }
        Texture texture;
        texture.width = uint32_t(image.width);
        texture.height = uint32_t(image.height);
        if (t.sampler >= 0) {
            if (size_t(t.sampler) >= model_.samplers.size())
                Fail(textureAt + ".sampler",
                     "sampler " + std::to_string(t.sampler) + " out of range");
            const tinygltf::Sampler& s = model_.samplers[size_t(t.sampler)];
            texture.wrapS = Wrap(s.wrapS);
            texture.wrapT = Wrap(s.wrapT);
            texture.filter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST
                                 ? TextureFilter::kNearest
                                 : TextureFilter::kLinear;
        }
        return textureIds_[info.index] = out_.scene.AddTexture(texture, rgba.data());
    }

    static TextureWrap Wrap(int mode) {
        if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::kClampToEdge;
        if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::kMirroredRepeat;
        return TextureWrap::kRepeat;
    }

    // The first animation's translation, rotation and scale channels as per-node keyframe clips,
    // looping over the animation's duration.
    void ReadAnimation() {
        if (model_.animations.empty()) return;
        if (model_.animations.size() > 1)
            Warn("animations", "animations: " + std::to_string(model_.animations.size()) +
                                   " animations; rtrt plays the first");
        const tinygltf::Animation& anim = model_.animations[0];
        std::map<int32_t, physics::KeyframeClip> clips;
        float duration = 0.0f;
        for (size_t c = 0; c < anim.channels.size(); ++c) {
            const tinygltf::AnimationChannel& ch = anim.channels[c];
            const std::string at = JsonIndexed("animations[0].channels", c);
            if (ch.target_path == "weights") {
                Warn("morph", at + ".target.path: weights (morph targets) are not "
                                   "supported; meshes keep their base shape");
                continue;
            }
            if (ch.target_path != "translation" && ch.target_path != "rotation" &&
                ch.target_path != "scale")
                Fail(at + ".target.path", "unknown path \"" + ch.target_path + "\"");
            if (ch.target_node < 0 || size_t(ch.target_node) >= model_.nodes.size())
                Fail(at + ".target.node",
                     "node " + std::to_string(ch.target_node) + " out of range");
            if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
                Fail(at + ".sampler", "sampler " + std::to_string(ch.sampler) + " out of range");
            const int32_t slot = nodeSlot_[size_t(ch.target_node)];
            if (slot < 0) continue;  // a node outside the scene shown
            const tinygltf::AnimationSampler& s = anim.samplers[size_t(ch.sampler)];
            const std::string samplerAt = JsonIndexed("animations[0].samplers", size_t(ch.sampler));
            physics::Interpolation mode = physics::Interpolation::kLinear;
            const bool cubic = s.interpolation == "CUBICSPLINE";
            if (s.interpolation == "STEP")
                mode = physics::Interpolation::kStep;
            else if (cubic)
                Warn("cubic", samplerAt +
                                  ".interpolation: CUBICSPLINE is played as LINEAR "
                                  "between its values (tangents ignored)");
            else if (s.interpolation != "LINEAR" && !s.interpolation.empty())
                Fail(samplerAt + ".interpolation", "unknown \"" + s.interpolation + "\"");
            std::vector<float> times;
            try {
                for (const glm::vec<1, float>& t :
                     ReadFloats<1>(s.input, samplerAt + ".input", TINYGLTF_TYPE_SCALAR))
                    times.push_back(t.x);
            } catch (const Unsupported& u) {
                Warn("unsupported:" + u.what, at + ": " + u.what + "; the channel is skipped");
                continue;
            }
            const size_t perKey = cubic ? 3 : 1;
            auto values = [&](auto read) {
                auto all = read();
                if (all.size() != times.size() * perKey)
                    Fail(samplerAt + ".output", std::to_string(all.size()) + " values for " +
                                                    std::to_string(times.size()) + " key times");
                decltype(all) keys;
                for (size_t k = 0; k < times.size(); ++k)
                    keys.push_back(all[k * perKey + perKey / 2]);
                return keys;
            };
            physics::KeyframeClip& clip = clips[slot];
            try {
                if (ch.target_path == "rotation") {
                    const auto v = values([&] {
                        return ReadFloats<4>(s.output, samplerAt + ".output", TINYGLTF_TYPE_VEC4);
                    });
                    clip.rotation.times = times;
                    for (const glm::vec4& q : v) {
                        const glm::dquat r(q.w, q.x, q.y, q.z);
                        if (!(glm::length(r) > 0.0))
                            Fail(samplerAt + ".output", "a rotation quaternion is zero");
                        clip.rotation.values.push_back(glm::quat(glm::normalize(r)));
                    }
                    clip.rotation.interpolation = mode == physics::Interpolation::kStep
                                                      ? mode
                                                      : physics::Interpolation::kSlerp;
                } else {
                    physics::Vec3Track& track =
                        ch.target_path == "translation" ? clip.translation : clip.scale;
                    track.times = times;
                    track.values = values([&] {
                        return ReadFloats<3>(s.output, samplerAt + ".output", TINYGLTF_TYPE_VEC3);
                    });
                    track.interpolation = mode;
                }
            } catch (const Unsupported& u) {
                Warn("unsupported:" + u.what, at + ": " + u.what + "; the channel is skipped");
                continue;
            }
            if (!times.empty()) duration = std::max(duration, times.back());
            clip.wrap = physics::WrapMode::kLoop;
            if (const std::string problem = physics::ValidateClip(clip); !problem.empty())
                Fail(samplerAt + ".input", problem);
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
            asset_.nodes[size_t(slot)].clip = std::make_shared<const physics::KeyframeClip>(clip);
            asset_.summary.animatedNodes++;
        }
        asset_.summary.animationSeconds = duration;
    }

    std::string file_;
    LoadedScene& out_;
    tinygltf::Model model_;
    GltfAsset asset_;
    std::vector<int> parentOf_;
    std::vector<int32_t> nodeSlot_;  // glTF node -> index in asset_.nodes, -1 outside the scene
    std::map<size_t, std::vector<std::pair<uint32_t, uint32_t>>> meshPrimitives_;
    std::map<int, uint32_t> materialIds_, textureIds_;
    uint32_t defaultMaterial_ = UINT32_MAX;
    std::set<std::string> warned_;
};

// A camera that sees the whole scene from the front (+z), a little above and to the right, so
// that a box shows three faces.
Camera FramingCamera(const LoadedScene& out) {
    const std::vector<glm::mat4> worlds = InitialWorlds(out);
    Aabb bounds;
    for (size_t i = 0; i < out.entities.size(); ++i) {
        const EntityDesc& e = out.entities[i];
        if (!e.renderable) continue;
        const Aabb b = out.scene.blases[e.blasId]->bounds;
        for (int corner = 0; corner < 8; ++corner) {
            const vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                         (corner & 4) ? b.max.z : b.min.z);
            bounds.Grow(vec3(worlds[i] * glm::vec4(p, 1.0f)));
        }
    }
    Camera camera;
    const vec3 centre = 0.5f * (bounds.min + bounds.max);
    const float radius = std::max(0.5f * glm::length(bounds.Extent()), 1e-3f);
    const float distance = radius / std::tan(glm::radians(0.5f * camera.fovYDegrees));
    const vec3 from = glm::normalize(vec3(0.6f, 0.5f, 1.0f));
    camera.position = centre + from * (distance * 1.1f);
    camera.forward = -from;
    return camera;
}

}  // namespace

bool IsGltfPath(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".gltf" || ext == ".glb";
}

GltfAsset LoadGltfAsset(const std::string& path, LoadedScene& out) {
    return Importer(path, out).Run();
}

std::optional<Camera> InstantiateGltf(const GltfAsset& asset, LoadedScene& out, int32_t parent,
                                      const glm::mat4& parentWorld) {
    std::optional<Camera> camera;
    std::vector<int32_t> entity(asset.nodes.size());
    std::vector<glm::mat4> world(asset.nodes.size());
    for (size_t i = 0; i < asset.nodes.size(); ++i) {
        const GltfNode& node = asset.nodes[i];
        const int32_t up = node.parent >= 0 ? entity[size_t(node.parent)] : parent;
        world[i] = (node.parent >= 0 ? world[size_t(node.parent)] : parentWorld) *
                   physics::ToMatrix(node.local);
        EntityDesc e;
        e.renderable = false;
        e.parent = up;
        e.sourceArray = "nodes";
        e.sourceIndex = node.source;
        e.local = node.local;
        if (node.clip) {
            physics::Animator animator;
            animator.clip = node.clip;
            animator.base = node.local;
            e.animator = animator;
        }
        entity[i] = int32_t(out.entities.size());
        out.entities.push_back(e);
        for (const auto& [blas, material] : node.primitives) {
            EntityDesc p;
            p.blasId = blas;
            p.materialId = material;
            p.parent = entity[i];
            p.sourceArray = "nodes";
            p.sourceIndex = node.source;
            out.entities.push_back(p);
        }
        const vec3 origin = vec3(world[i] * glm::vec4(0, 0, 0, 1));
        if (node.light >= 0) {
            const GltfLight& l = asset.lights[size_t(node.light)];
            Light light;
            light.type = l.type;
            light.color = l.color;
            // Directional lights shine along the node's -z: the direction toward them is +z.
            const vec3 toward = vec3(world[i] * glm::vec4(0, 0, 1, 0));
            light.vector =
                l.type == LightType::kPoint
                    ? origin
                    : (glm::length(toward) > 0.0f ? glm::normalize(toward) : vec3(0, 0, 1));
            out.scene.lights.push_back(light);
        }
        if (node.camera >= 0 && !camera) {
            Camera c;
            c.position = origin;
            c.forward = vec3(world[i] * glm::vec4(0, 0, -1, 0));
            c.up = vec3(world[i] * glm::vec4(0, 1, 0, 0));
            c.fovYDegrees = asset.cameras[size_t(node.camera)].fovYDegrees;
            if (glm::length(glm::cross(c.forward, c.up)) > 0.0f) camera = c;
        }
    }
    return camera;
}

LoadedScene LoadGltfScene(const std::string& path) {
    LoadedScene out;
    const GltfAsset asset = LoadGltfAsset(path, out);
    out.gltfFiles.push_back(asset.summary);
    const std::optional<Camera> camera = InstantiateGltf(asset, out, -1, glm::mat4(1.0f));
    bool anything = false;
    for (const EntityDesc& e : out.entities) anything |= e.renderable;
    if (!anything) throw InputError(path, "meshes", "the scene has no triangles to render");
    if (camera) {
        out.scene.camera = *camera;
        for (const GltfNode& n : asset.nodes)
            if (n.camera >= 0) {
                const float aspect = asset.cameras[size_t(n.camera)].aspect;
                if (aspect > 0.0f) {
                    out.width = 1280;
                    out.height = uint32_t(std::clamp(std::lround(1280.0f / aspect), 1L, 16384L));
                }
                break;
            }
    } else {
        out.scene.camera = FramingCamera(out);
    }
    if (out.scene.lights.empty()) {
        Light light;
        light.vector = glm::normalize(vec3(1.0f, 1.0f, 1.0f));
        out.scene.lights.push_back(light);
    }
    FinishLoadedScene(out, path);
    return out;
}

}  // namespace rtrt
