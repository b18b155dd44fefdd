#pragma once
// The header of a Stanford PLY file: its format, its elements and their properties, and where a
// triangle mesh's data sit among them (ply_reader.cpp reads the body by it).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rtrt {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };
enum class ScalarType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct PlyProperty {
    std::string name;
    ScalarType type;  // of the value, or of a list's items
    bool isList = false;
    ScalarType countType = ScalarType::kUint8;
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

struct PlyHeader {
    PlyFormat format = PlyFormat::kAscii;
    std::vector<PlyElement> elements;
    size_t dataOffset = 0;
};

// Where the vertex and face data sit among the elements and their properties.
struct PlyLayout {
    const PlyElement* vertices = nullptr;
    const PlyElement* faces = nullptr;
    const PlyElement* strips = nullptr;  // "tristrips": strips of triangles, -1 ends one
    std::array<int, 6> vertexProperty{-1, -1, -1, -1, -1, -1};  // x y z nx ny nz
    int faceIndexProperty = -1;
    int stripIndexProperty = -1;
    bool hasNormals = false;
    // red green blue (or diffuse_red diffuse_green diffuse_blue), where all three are there.
    std::array<int, 3> colorProperty{-1, -1, -1};
    bool hasColors = false;
};

size_t SizeOf(ScalarType type);
bool IsInteger(ScalarType type);

// The header lines of DATA, up to end_header; InputError naming PATH and "header line N".
PlyHeader ParsePlyHeaderLines(const std::string& path, std::string_view data);

// Rejects element counts that DATABYTES of body could not hold, before anything is allocated.
void CheckPlyCounts(const std::string& path, const PlyHeader& header, size_t dataBytes);

// The vertex, face and tristrips elements and the properties rtrt reads from them.
PlyLayout FindPlyLayout(const std::string& path, const PlyHeader& header);

}  // namespace rtrt
