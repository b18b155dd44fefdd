#include "game/assets/mesh_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/core/error.h"
#include "engine/geometry/smooth_normals.h"

namespace rtrt::mesh_text {

std::string_view NextWord(std::string_view& line) {
    size_t start = 0;
    while (start < line.size() && IsSpace(line[start])) ++start;
    size_t end = start;
    while (end < line.size() && !IsSpace(line[end])) ++end;
    std::string_view word = line.substr(start, end - start);
    line.remove_prefix(end);
    return word;
}

// Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "'" + std::string.
std::string Quote(std::string_view token) {
    constexpr size_t kMaxShown = 32;
    std::string quoted = "'";
    quoted += WithoutControlCharacters(token.substr(0, kMaxShown));
    quoted += token.size() > kMaxShown ? "...'" : "'";
    return quoted;
}

float ParseCoordinate(std::string_view token, bool refuseBeyondFloat) {
    double value = 0.0;
    if (!ParseNumber(token, value)) throw RecordError{"expected a number, found " + Quote(token)};
    if (refuseBeyondFloat && std::isfinite(value) &&
        std::fabs(value) > std::numeric_limits<float>::max()) {
        throw RecordError{"number " + Quote(token) + " is beyond the float range (3.4e38)"};
    }
    return static_cast<float>(value);
}

bool NormalizeFileNormal(vec3& normal) {
    const float length = glm::length(normal);
    if (!(length > 0.0f) || !std::isfinite(length)) return false;
    normal /= length;
    return true;
}

void KeepFileNormals(TriangleMesh& mesh) {
    std::vector<vec3> file = std::move(mesh.normals);
    std::vector<size_t> undirected;
    for (size_t v = 0; v < file.size(); ++v)
        if (!NormalizeFileNormal(file[v])) undirected.push_back(v);
    if (!undirected.empty()) {
        ComputeSmoothNormals(mesh);
        for (size_t v : undirected) file[v] = mesh.normals[v];
    }
    mesh.normals = std::move(file);
}

void ClampColors(const std::string& file, std::vector<vec3>& colors) {
    uint64_t outside = 0;
    for (vec3& color : colors)
        for (int k = 0; k < 3; ++k)
            if (color[k] < 0.0f || color[k] > 1.0f) {
                ++outside;
                color[k] = std::clamp(color[k], 0.0f, 1.0f);
            }
    if (outside > 0)
        std::fprintf(stderr,
                     "rtrt: warning: %s: %llu vertex colour components outside [0, 1] are "
                     "clamped\n",
                     WithoutControlCharacters(file).c_str(),
                     static_cast<unsigned long long>(outside));
}

void WarnOfFannedPolygons(const std::string& file, const PolygonTriangulator& triangulator) {
    if (triangulator.NoEar() > 0)
        std::fprintf(stderr,
                     "rtrt: warning: %s: %llu polygons cross or fold over themselves; "
                     "filled as fans from their first corner\n",
                     WithoutControlCharacters(file).c_str(),
                     static_cast<unsigned long long>(triangulator.NoEar()));
    if (triangulator.OverBudget() > 0)
        std::fprintf(stderr,
                     "rtrt: warning: %s: %llu concave polygons past the file's budget of ear "
                     "tests filled as fans from their first corner; split them into smaller "
                     "polygons in the modelling tool\n",
                     WithoutControlCharacters(file).c_str(),
                     static_cast<unsigned long long>(triangulator.OverBudget()));
}

void WarnOfShortFaces(const std::string& file, uint64_t count) {
    if (count == 0) return;
    std::fprintf(stderr,
                 "rtrt: warning: %s: %llu faces of fewer than 3 corners (lines or points, no "
                 "surface) skipped\n",
                 WithoutControlCharacters(file).c_str(), static_cast<unsigned long long>(count));
}

void CheckTriangleCount(uint64_t triangles) {
    if (triangles < kMaxTriangles) return;
    throw RecordError{"over " + std::to_string(kMaxTriangles) +
                      " triangles: more than rtrt takes in one mesh"};
}

}  // namespace rtrt::mesh_text
