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

TriangleMesh LoadMesh(const std::string& path, uint64_t* fileVertices) {
    std::string name = ToLower(std::filesystem::path(path).filename().string());
    TriangleMesh mesh;
    uint64_t objVertices = 0;
    const bool obj = EndsWith(name, ".obj");
    if (obj) {
        mesh = ParseObj(path, ReadPlainFile(path), &objVertices);
    } else if (EndsWith(name, ".ply.gz")) {
        mesh = ParsePly(path, ReadGzipFile(path));
    } else if (EndsWith(name, ".ply")) {
        mesh = ParsePly(path, ReadPlainFile(path));
    } else {
        throw InputError(path, "", "unknown mesh file extension (expected .obj, .ply or .ply.gz)");
    }
    if (mesh.indices.empty()) throw InputError(path, "", "contains no triangles");
    if (fileVertices) *fileVertices = obj ? objVertices : mesh.positions.size();
    return mesh;
}

}  // namespace rtrt
