#include "game/assets/ply_reader.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/geometry/smooth_normals.h"
#include "game/assets/mesh_text.h"

namespace rtrt {
namespace {

using mesh_text::IsSpace;
using mesh_text::kMaxVertices;
using mesh_text::NextWord;
using mesh_text::NormalizeFileNormals;
using mesh_text::ParseNumber;
using mesh_text::Quote;
using mesh_text::RecordError;

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

bool ParseScalarType(std::string_view name, ScalarType& type) {
    struct Named {
        std::string_view name;
        ScalarType type;
    };
    static constexpr std::array<Named, 16> kTypes = {{
        {"char", ScalarType::kInt8},
        {"int8", ScalarType::kInt8},
        {"uchar", ScalarType::kUint8},
        {"uint8", ScalarType::kUint8},
        {"short", ScalarType::kInt16},
        {"int16", ScalarType::kInt16},
        {"ushort", ScalarType::kUint16},
        {"uint16", ScalarType::kUint16},
        {"int", ScalarType::kInt32},
        {"int32", ScalarType::kInt32},
        {"uint", ScalarType::kUint32},
        {"uint32", ScalarType::kUint32},
        {"float", ScalarType::kFloat32},
        {"float32", ScalarType::kFloat32},
        {"double", ScalarType::kFloat64},
        {"float64", ScalarType::kFloat64},
    }};
    for (const Named& named : kTypes) {
        if (named.name == name) {
            type = named.type;
            return true;
        }
    }
    return false;
}

size_t SizeOf(ScalarType type) {
    switch (type) {
        case ScalarType::kInt8:
        case ScalarType::kUint8:
            return 1;
        case ScalarType::kInt16:
        case ScalarType::kUint16:
            return 2;
        case ScalarType::kInt32:
        case ScalarType::kUint32:
        case ScalarType::kFloat32:
            return 4;
        case ScalarType::kFloat64:
            return 8;
    }
    return 8;
}

bool IsInteger(ScalarType type) {
    return type != ScalarType::kFloat32 && type != ScalarType::kFloat64;
}

std::vector<std::string_view> SplitWords(std::string_view line) {
    std::vector<std::string_view> words;
    for (std::string_view word = NextWord(line); !word.empty(); word = NextWord(line)) {
        words.push_back(word);
    }
    return words;
}

PlyFormat ParsePlyFormat(const std::string& path, const std::string& field,
                         const std::vector<std::string_view>& words) {
    double version = 0.0;
    if (words.size() != 3 || !ParseNumber(words[2], version) || version != 1.0) {
        throw InputError(path, field, "expected 'format <type> 1.0'");
    }
    if (words[1] == "ascii") return PlyFormat::kAscii;
    if (words[1] == "binary_little_endian") return PlyFormat::kBinaryLittleEndian;
    if (words[1] == "binary_big_endian") return PlyFormat::kBinaryBigEndian;
    throw InputError(path, field, "unknown format " + Quote(words[1]));
}

// Parses "property <type> <name>" or "property list <count type> <item type> <name>".
PlyProperty ParsePlyProperty(const std::string& path, const std::string& field,
                             const std::vector<std::string_view>& words) {
    PlyProperty property;
    property.name = words.back();
    if (words.size() == 3 && ParseScalarType(words[1], property.type)) return property;
    property.isList = true;
    if (words.size() != 5 || words[1] != "list" || !ParseScalarType(words[2], property.countType) ||
        !ParseScalarType(words[3], property.type)) {
        throw InputError(path, field,
                         "expected 'property <type> <name>' or 'property list <count type> "
                         "<item type> <name>' with known types");
    }
    if (!IsInteger(property.countType)) {
        throw InputError(path, field, "list count type must be an integer type");
    }
    return property;
}

// Reads the header up to end_header; throws on anything it does not understand.
PlyHeader ParsePlyHeaderLines(const std::string& path, std::string_view data) {
    if (data.substr(0, 3) != "ply" || data.size() < 4 || (data[3] != '\n' && data[3] != '\r')) {
        throw InputError(path, "header", "bad magic (not a PLY file)");
    }
    // Lines end as the first one does. Old Mac tools end them with a lone CR; a CR-LF header's CR
    // is trimmed with the words. Deciding once keeps a binary body whose first byte is 0x0A
    // after an "end_header\r" from being taken for the rest of a line end.
    const char lineEnd = data[3] == '\r' && (data.size() < 5 || data[4] != '\n') ? '\r' : '\n';
    PlyHeader header;
    bool haveFormat = false;
    size_t offset = 0;
    for (size_t lineNumber = 1;; ++lineNumber) {
        size_t newline = data.find(lineEnd, offset);
        std::string field = "header line " + std::to_string(lineNumber);
        if (newline == std::string_view::npos) {
            throw InputError(path, field, "no end_header (truncated header)");
        }
        std::vector<std::string_view> words = SplitWords(data.substr(offset, newline - offset));
        offset = newline + 1;
        if (lineNumber == 1 || words.empty()) continue;
        std::string_view keyword = words[0];
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            if (!haveFormat) throw InputError(path, field, "end_header before the format line");
            header.dataOffset = offset;
            return header;
        }
        if (keyword == "format") {
            header.format = ParsePlyFormat(path, field, words);
            haveFormat = true;
        } else if (keyword == "element") {
            PlyElement element;
            if (words.size() != 3 || !ParseNumber(words[2], element.count)) {
                throw InputError(path, field, "expected 'element <name> <count>'");
            }
            element.name = words[1];
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty()) throw InputError(path, field, "property before element");
            header.elements.back().properties.push_back(ParsePlyProperty(path, field, words));
        } else {
            throw InputError(path, field, "unknown keyword " + Quote(keyword));
        }
    }
}

// Where the vertex and face data sit among the elements and their properties.
struct PlyLayout {
    const PlyElement* vertices = nullptr;
    const PlyElement* faces = nullptr;
    std::array<int, 6> vertexProperty{-1, -1, -1, -1, -1, -1};  // x y z nx ny nz
    int faceIndexProperty = -1;
    bool hasNormals = false;
};

int FindProperty(const PlyElement& element, std::string_view name) {
    for (size_t i = 0; i < element.properties.size(); ++i) {
        if (element.properties[i].name == name) return static_cast<int>(i);
    }
    return -1;
}

// Rejects element counts that the data could not hold, before anything is allocated for them.
// A record takes at least its binary values' sizes (a list its count's), or in ASCII one character
// and one separator per value; the final newline of an ASCII file is optional.
void CheckPlyCounts(const std::string& path, const PlyHeader& header, size_t dataBytes) {
    bool ascii = header.format == PlyFormat::kAscii;
    uint64_t available = dataBytes + (ascii ? 1 : 0), needed = 0;
    for (const PlyElement& element : header.elements) {
        uint64_t recordBytes = 0;
        for (const PlyProperty& p : element.properties) {
            recordBytes += ascii ? 2 : SizeOf(p.isList ? p.countType : p.type);
        }
        if (element.count == 0) continue;
        if (recordBytes == 0) {
            throw InputError(path, "header",
                             "element " + Quote(element.name) + " has no properties");
        }
        if (element.count > (available - needed) / recordBytes) {
            throw InputError(path, "header",
                             "element " + Quote(element.name) + " declares " +
                                 std::to_string(element.count) + " records, more than the " +
                                 std::to_string(dataBytes) + " bytes of data can hold");
        }
        needed += element.count * recordBytes;
    }
}

const PlyElement* FindElement(const std::string& path, const PlyHeader& header,
                              std::string_view name) {
    const PlyElement* found = nullptr;
    for (const PlyElement& element : header.elements) {
        if (element.name != name) continue;
        if (found) throw InputError(path, "header", "more than one element " + Quote(name));
        found = &element;
    }
    return found;
}

PlyLayout FindPlyLayout(const std::string& path, const PlyHeader& header) {
    PlyLayout layout;
    layout.vertices = FindElement(path, header, "vertex");
    layout.faces = FindElement(path, header, "face");
    if (!layout.vertices) throw InputError(path, "header", "no vertex element");
    if (layout.vertices->count > kMaxVertices) {
        throw InputError(path, "header", "more than 2^32 - 1 vertices");
    }
    static constexpr std::array<std::string_view, 6> kNames = {"x", "y", "z", "nx", "ny", "nz"};
    for (size_t i = 0; i < kNames.size(); ++i) {
        int index = FindProperty(*layout.vertices, kNames[i]);
        if (index >= 0 && layout.vertices->properties[index].isList) {
            throw InputError(path, "header", "vertex property " + Quote(kNames[i]) + " is a list");
        }
        if (index < 0 && i < 3) {
            throw InputError(path, "header", "vertex element has no property " + Quote(kNames[i]));
        }
        layout.vertexProperty[i] = index;
    }
    layout.hasNormals = layout.vertexProperty[3] >= 0 && layout.vertexProperty[4] >= 0 &&
                        layout.vertexProperty[5] >= 0;
    if (!layout.faces) return layout;
    layout.faceIndexProperty = FindProperty(*layout.faces, "vertex_indices");
    if (layout.faceIndexProperty < 0) {
        layout.faceIndexProperty = FindProperty(*layout.faces, "vertex_index");
    }
    if (layout.faceIndexProperty < 0) {
        throw InputError(path, "header", "face element has no vertex_indices list");
    }
    const PlyProperty& indices = layout.faces->properties[layout.faceIndexProperty];
    if (!indices.isList || !IsInteger(indices.type)) {
        throw InputError(path, "header", "face vertex_indices must be a list of integers");
    }
    return layout;
}

const RecordError kTruncated{"unexpected end of data (file truncated)"};

class AsciiReader {
  public:
    explicit AsciiReader(std::string_view data) : p_(data.data()), end_(p_ + data.size()) {}

    double ReadReal(ScalarType type) {
        std::string_view token = Token();
        if (type == ScalarType::kFloat32) {
            float value = 0.0f;
            if (ParseNumber(token, value)) return value;
        }
        double value = 0.0;
        if (!ParseNumber(token, value)) {
            throw RecordError{"expected a number, found " + Quote(token)};
        }
        return value;
    }
    int64_t ReadInteger(ScalarType) {
        std::string_view token = Token();
        int64_t value = 0;
        if (!ParseNumber(token, value)) {
            throw RecordError{"expected an integer, found " + Quote(token)};
        }
        return value;
    }
    void Skip(ScalarType) { Token(); }
    void SkipItems(ScalarType type, uint64_t count) {
        for (uint64_t i = 0; i < count; ++i) Skip(type);
    }

  private:
    std::string_view Token() {
        while (p_ != end_ && IsSpace(*p_)) ++p_;
        if (p_ == end_) throw kTruncated;
        const char* start = p_;
        while (p_ != end_ && !IsSpace(*p_)) ++p_;
        return std::string_view(start, static_cast<size_t>(p_ - start));
    }

    const char* p_;
    const char* end_;
};

template <class T>
T LoadScalar(const char* p, bool swapBytes) {
    using Bits = std::conditional_t<
        sizeof(T) == 1, uint8_t,
        std::conditional_t<sizeof(T) == 2, uint16_t,
                           std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>>;
    Bits bits;
    std::memcpy(&bits, p, sizeof(bits));
    if (swapBytes) {
        if constexpr (sizeof(T) == 2) bits = __builtin_bswap16(bits);
        if constexpr (sizeof(T) == 4) bits = __builtin_bswap32(bits);
        if constexpr (sizeof(T) == 8) bits = __builtin_bswap64(bits);
    }
    return std::bit_cast<T>(bits);
}

class BinaryReader {
  public:
    BinaryReader(std::string_view data, bool swapBytes)
        : p_(data.data()), end_(p_ + data.size()), swapBytes_(swapBytes) {}

    double ReadReal(ScalarType type) {
        switch (type) {
            case ScalarType::kFloat32:
                return Take<float>();
            case ScalarType::kFloat64:
                return Take<double>();
            default:
                return static_cast<double>(ReadInteger(type));
        }
    }
    int64_t ReadInteger(ScalarType type) {
        switch (type) {
            case ScalarType::kInt8:
                return Take<int8_t>();
            case ScalarType::kUint8:
                return Take<uint8_t>();
            case ScalarType::kInt16:
                return Take<int16_t>();
            case ScalarType::kUint16:
                return Take<uint16_t>();
            case ScalarType::kInt32:
                return Take<int32_t>();
            case ScalarType::kUint32:
                return Take<uint32_t>();
            default:
                throw RecordError{"expected an integer type"};
        }
    }
    void Skip(ScalarType type) { SkipItems(type, 1); }
    void SkipItems(ScalarType type, uint64_t count) {
        if (count > static_cast<uint64_t>(end_ - p_) / SizeOf(type)) throw kTruncated;
        p_ += count * SizeOf(type);
    }

  private:
    template <class T>
    T Take() {
        if (static_cast<size_t>(end_ - p_) < sizeof(T)) throw kTruncated;
        T value = LoadScalar<T>(p_, swapBytes_);
        p_ += sizeof(T);
        return value;
    }

    const char* p_;
    const char* end_;
    bool swapBytes_;
};

template <class Reader>
void SkipList(Reader& reader, const PlyProperty& property) {
    int64_t count = reader.ReadInteger(property.countType);
    if (count < 0) throw RecordError{"negative list length " + std::to_string(count)};
    reader.SkipItems(property.type, static_cast<uint64_t>(count));
}

template <class Reader>
void SkipProperty(Reader& reader, const PlyProperty& property) {
    if (property.isList) {
        SkipList(reader, property);
    } else {
        reader.Skip(property.type);
    }
}

template <class Reader>
void ReadPlyVertices(Reader& reader, const PlyLayout& layout, uint64_t& record,
                     TriangleMesh& mesh) {
    const std::vector<PlyProperty>& properties = layout.vertices->properties;
    std::vector<int> slotOf(properties.size(), -1);
    for (int slot = 0; slot < (layout.hasNormals ? 6 : 3); ++slot) {
        slotOf[layout.vertexProperty[slot]] = slot;
    }
    for (; record < layout.vertices->count; ++record) {
        std::array<float, 6> values{};
        for (size_t i = 0; i < properties.size(); ++i) {
            if (slotOf[i] < 0) {
                SkipProperty(reader, properties[i]);
            } else {
                values[slotOf[i]] = static_cast<float>(reader.ReadReal(properties[i].type));
            }
        }
        vec3 position(values[0], values[1], values[2]);
        if (!IsFinite(position)) throw RecordError{"coordinate is NaN or infinite"};
        mesh.positions.push_back(position);
        if (layout.hasNormals) mesh.normals.emplace_back(values[3], values[4], values[5]);
    }
}

template <class Reader>
void ReadPlyFaces(Reader& reader, const PlyLayout& layout, uint64_t& record, TriangleMesh& mesh) {
    const std::vector<PlyProperty>& properties = layout.faces->properties;
    const PlyProperty& indexProperty = properties[layout.faceIndexProperty];
    int64_t vertexCount = static_cast<int64_t>(layout.vertices->count);
    for (; record < layout.faces->count; ++record) {
        for (size_t i = 0; i < properties.size(); ++i) {
            if (static_cast<int>(i) != layout.faceIndexProperty) {
                SkipProperty(reader, properties[i]);
                continue;
            }
            int64_t corners = reader.ReadInteger(indexProperty.countType);
            if (corners < 0) throw RecordError{"negative vertex count " + std::to_string(corners)};
            uint32_t first = 0, previous = 0;
            for (int64_t corner = 0; corner < corners; ++corner) {
                int64_t index = reader.ReadInteger(indexProperty.type);
                if (index < 0 || index >= vertexCount) {
                    throw RecordError{"vertex index " + std::to_string(index) + " out of range (" +
                                      std::to_string(vertexCount) + " vertices)"};
                }
                uint32_t current = static_cast<uint32_t>(index);
                if (corner == 0) first = current;
                if (corner >= 2 && first != previous && previous != current && first != current) {
                    mesh_text::CheckTriangleCount(mesh.indices.size());
                    mesh.indices.emplace_back(first, previous, current);
                }
                previous = current;
            }
        }
    }
}

template <class Reader>
void ReadPlyBody(const std::string& path, const PlyHeader& header, const PlyLayout& layout,
                 size_t bodyBytes, Reader& reader, TriangleMesh& mesh) {
    mesh.positions.reserve(layout.vertices->count);
    if (layout.hasNormals) mesh.normals.reserve(layout.vertices->count);
    // A face count is bounded by the body only at a byte a face (an empty list), so the
    // reservation for triangles is bounded by what a mesh may hold and by the body's bytes at
    // four a triangle (a count and three one-byte indices): a header may not ask for gigabytes.
    if (layout.faces)
        mesh.indices.reserve(
            std::min({layout.faces->count, mesh_text::kMaxTriangles, uint64_t(bodyBytes / 4)}));
    for (const PlyElement& element : header.elements) {
        uint64_t record = 0;
        try {
            if (&element == layout.vertices) {
                ReadPlyVertices(reader, layout, record, mesh);
            } else if (&element == layout.faces) {
                ReadPlyFaces(reader, layout, record, mesh);
            } else {
                for (; record < element.count; ++record) {
                    for (const PlyProperty& property : element.properties) {
                        SkipProperty(reader, property);
                    }
                }
            }
        } catch (const RecordError& error) {
            throw InputError(path, element.name + " " + std::to_string(record), error.reason);
        }
    }
}

}  // namespace

TriangleMesh ParsePly(const std::string& path, std::string_view data) {
    PlyHeader header = ParsePlyHeaderLines(path, data);
    data.remove_prefix(header.dataOffset);
    CheckPlyCounts(path, header, data.size());
    PlyLayout layout = FindPlyLayout(path, header);
    TriangleMesh mesh;
    if (header.format == PlyFormat::kAscii) {
        AsciiReader reader(data);
        ReadPlyBody(path, header, layout, data.size(), reader, mesh);
    } else {
        bool bigEndianData = header.format == PlyFormat::kBinaryBigEndian;
        BinaryReader reader(data, bigEndianData != (std::endian::native == std::endian::big));
        ReadPlyBody(path, header, layout, data.size(), reader, mesh);
    }
    if (!layout.hasNormals || !NormalizeFileNormals(mesh.normals)) ComputeSmoothNormals(mesh);
    return mesh;
}

}  // namespace rtrt
