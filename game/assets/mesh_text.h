#pragma once
// What the OBJ and PLY readers share: record errors, number parsing and file normals.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/math.h"
#include "engine/geometry/triangle_mesh.h"
#include "game/assets/polygon_triangulation.h"

namespace rtrt::mesh_text {

constexpr uint64_t kMaxVertices = std::numeric_limits<uint32_t>::max();

// A problem inside one record (an OBJ line, a PLY element); the caller knows which record it is
// and rethrows it as an InputError.
struct RecordError {
    std::string reason;
};

// More than any model rtrt is used with (134M; the largest scanned statues have tens of
// millions), and a bound on what a small file of long polygon fans can make: a 2 GB file of them
// would otherwise ask for tens of gigabytes of triangles.
constexpr uint64_t kMaxTriangles = uint64_t{1} << 27;

// Throws a RecordError when a mesh of `triangles` triangles may not take another.
void CheckTriangleCount(uint64_t triangles);

inline bool IsSpace(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// Splits off the next whitespace-separated word of LINE.
std::string_view NextWord(std::string_view& line);

// TOKEN in quotes for a message, cut short when long.
std::string Quote(std::string_view token);

// Parses all of TOKEN as a number; from_chars rejects the leading '+' that some writers emit.
template <class T>
bool ParseNumber(std::string_view token, T& value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    auto [next, ec] = std::from_chars(token.data(), end, value);
    return ec == std::errc() && next == end;
}

// TOKEN as a float; RecordError when it is not a number, or (refuseBeyondFloat) a finite one
// beyond float's range, which would read as infinite.
float ParseCoordinate(std::string_view token, bool refuseBeyondFloat = true);

// A normal read from a file, normalised; false when it has no direction (zero, NaN, infinite).
bool NormalizeFileNormal(vec3& normal);

// COLORS, a file's vertex colours, clamped to [0, 1] (infinities too), with a warning naming FILE
// and how many components were outside.
void ClampColors(const std::string& file, std::vector<vec3>& colors);

// MESH.normals, one per vertex, are a file's: each is normalised, and one without a direction
// is replaced by the vertex's area-weighted normal (ComputeSmoothNormals), so that a few
// degenerate normals an exporter wrote do not cost the rest of the file its own.
void KeepFileNormals(TriangleMesh& mesh);

// Prints one warning on stderr for the polygons of FILE that TRIANGULATOR had to fan although
// they are concave; nothing when there are none.
void WarnOfFannedPolygons(const std::string& file, const PolygonTriangulator& triangulator);

// Prints one warning on stderr for the COUNT faces of FILE given fewer than three corners (loose
// edges, as older exporters wrote them), which have no surface and were skipped.
void WarnOfShortFaces(const std::string& file, uint64_t count);

}  // namespace rtrt::mesh_text
