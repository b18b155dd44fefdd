#include "game/assets/mesh_text.h"

#include <cstdio>

#include "engine/core/error.h"

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

float ParseCoordinate(std::string_view token) {
    double value = 0.0;
    if (!ParseNumber(token, value)) throw RecordError{"expected a number, found " + Quote(token)};
    return static_cast<float>(value);
}

bool NormalizeFileNormals(std::vector<vec3>& normals) {
    for (vec3& n : normals) {
        float length = glm::length(n);
        if (!(length > 0.0f) || !std::isfinite(length)) return false;
        n /= length;
    }
    return true;
}

void CheckTriangleCount(uint64_t triangles) {
    if (triangles < kMaxTriangles) return;
    throw RecordError{"over " + std::to_string(kMaxTriangles) +
                      " triangles: more than rtrt takes in one mesh"};
}

}  // namespace rtrt::mesh_text
