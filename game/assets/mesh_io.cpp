#include "game/assets/mesh_io.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <string_view>
#include <vector>

#include "engine/core/error.h"
#include "game/assets/file_bytes.h"
#include "game/assets/obj_reader.h"
#include "game/assets/ply_reader.h"

namespace rtrt {
namespace {

bool EndsWith(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

std::string ToLower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

}  // namespace

TriangleMesh LoadMesh(const std::string& path) {
    std::string name = ToLower(std::filesystem::path(path).filename().string());
    TriangleMesh mesh;
    if (EndsWith(name, ".obj")) {
        mesh = ParseObj(path, ReadPlainFile(path));
    } else if (EndsWith(name, ".ply.gz")) {
        mesh = ParsePly(path, ReadGzipFile(path));
    } else if (EndsWith(name, ".ply")) {
        mesh = ParsePly(path, ReadPlainFile(path));
    } else {
        throw InputError(path, "", "unknown mesh file extension (expected .obj, .ply or .ply.gz)");
    }
    if (mesh.indices.empty()) throw InputError(path, "", "contains no triangles");
    return mesh;
}

void ComputeSmoothNormals(TriangleMesh& mesh) {
    std::vector<vec3> normals(mesh.positions.size(), vec3(0.0f));
    for (const glm::uvec3& t : mesh.indices) {
        vec3 p0 = mesh.positions[t.x];
        // The cross product's length is twice the triangle's area: the sum is area-weighted.
        vec3 n = glm::cross(mesh.positions[t.y] - p0, mesh.positions[t.z] - p0);
        normals[t.x] += n;
        normals[t.y] += n;
        normals[t.z] += n;
    }
    for (vec3& n : normals) {
        float length = glm::length(n);
        n = length > 0.0f && std::isfinite(length) ? n / length : vec3(0.0f, 1.0f, 0.0f);
    }
    mesh.normals = std::move(normals);
}

}  // namespace rtrt
