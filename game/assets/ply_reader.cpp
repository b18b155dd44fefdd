#include "game/assets/ply_reader.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/geometry/smooth_normals.h"
#include "game/assets/mesh_text.h"
#include "game/assets/ply_header.h"
#include "game/assets/polygon_triangulation.h"

namespace rtrt {
namespace {

using mesh_text::IsSpace;
using mesh_text::ParseNumber;
using mesh_text::Quote;
using mesh_text::RecordError;

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
    // Not held to the declared type's range: Blender's exporter declares uchar counts and writes
    // n-gons of more than 255 corners in ASCII. A count that does not match the line is caught
    // when the line ends early or has values left over.
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
    // Each record is one line: values left on it, or a record that goes on past it, mean the
    // data does not follow the header (a shifted file had loaded as another mesh).
    void EndRecord() {
        while (p_ != end_ && !IsLineEnd(*p_) && IsSpace(*p_)) ++p_;
        if (p_ != end_ && !IsLineEnd(*p_))
            throw RecordError{"more values on the line than the header's properties (" +
                              Quote(Token()) + ")"};
        valuesInRecord_ = 0;
    }
    // Whitespace alone may follow the last record: text is records the header does not announce.
    static constexpr bool kLeftoverIsError = true;
    std::optional<std::string> Leftover() {
        // NUL padding and a DOS end-of-file mark (^Z) count as nothing.
        while (p_ != end_ && (IsSpace(*p_) || *p_ == '\0' || *p_ == '\x1a')) ++p_;
        if (p_ == end_) return std::nullopt;
        return "text after the last record the header announces (" + Quote(Token()) + ")";
    }

  private:
    std::string_view Token() {
        while (p_ != end_ && IsSpace(*p_)) {
            if (IsLineEnd(*p_) && valuesInRecord_ > 0)
                throw RecordError{
                    "the line ends before the record does (fewer values than the "
                    "header's properties)"};
            ++p_;
        }
        if (p_ == end_) throw kTruncated;
        const char* start = p_;
        while (p_ != end_ && !IsSpace(*p_)) ++p_;
        ++valuesInRecord_;
        return std::string_view(start, static_cast<size_t>(p_ - start));
    }
    // Lines end in LF, CR LF or CR alone.
    static bool IsLineEnd(char c) { return c == '\n' || c == '\r'; }
    const char* p_;
    const char* end_;
    uint64_t valuesInRecord_ = 0;
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
    void EndRecord() {}
    // Bytes after the last record: records the header does not announce (a file of one face more
    // than announced had lost it without a word), or padding some writer left; a warning, since
    // binary data cannot tell which.
    static constexpr bool kLeftoverIsError = false;
    std::optional<std::string> Leftover() const {
        if (p_ == end_) return std::nullopt;
        return std::to_string(end_ - p_) +
               " bytes after the last record the header announces are ignored (do its counts "
               "match the data?)";
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

// A colour channel as a fraction: integers of their type's largest value (255 for the usual
// uchar), floats as they are; bounded (NaN stays NaN) so that a double beyond float's range is
// clamped like any value above 1 rather than read as infinite.
float NormalizedColor(double value, ScalarType type) {
    double largest = 1.0;
    switch (type) {
        case ScalarType::kInt8:
            largest = 127.0;
            break;
        case ScalarType::kUint8:
            largest = 255.0;
            break;
        case ScalarType::kInt16:
            largest = 32767.0;
            break;
        case ScalarType::kUint16:
            largest = 65535.0;
            break;
        case ScalarType::kInt32:
            largest = 2147483647.0;
            break;
        case ScalarType::kUint32:
            largest = 4294967295.0;
            break;
        default:
            break;
    }
    return float(std::clamp(value / largest, -1.0, 2.0));
}

template <class Reader>
void ReadPlyVertices(Reader& reader, const PlyLayout& layout, uint64_t& record,
                     TriangleMesh& mesh) {
    const std::vector<PlyProperty>& properties = layout.vertices->properties;
    std::vector<int> slotOf(properties.size(), -1);
    for (int slot = 0; slot < (layout.hasNormals ? 6 : 3); ++slot) {
        slotOf[layout.vertexProperty[slot]] = slot;
    }
    if (layout.hasColors)
        for (int k = 0; k < 3; ++k) slotOf[layout.colorProperty[k]] = 6 + k;
    for (; record < layout.vertices->count; ++record) {
        std::array<float, 9> values{};
        for (size_t i = 0; i < properties.size(); ++i) {
            if (slotOf[i] < 0) {
                SkipProperty(reader, properties[i]);
            } else if (slotOf[i] >= 6) {
                values[slotOf[i]] =
                    NormalizedColor(reader.ReadReal(properties[i].type), properties[i].type);
            } else {
                values[slotOf[i]] = static_cast<float>(reader.ReadReal(properties[i].type));
            }
        }
        reader.EndRecord();
        vec3 position(values[0], values[1], values[2]);
        if (!IsFinite(position)) throw RecordError{"coordinate is NaN or infinite"};
        mesh.positions.push_back(position);
        if (layout.hasNormals) mesh.normals.emplace_back(values[3], values[4], values[5]);
        if (layout.hasColors) {
            const vec3 color(values[6], values[7], values[8]);
            if (!IsFinite(color)) throw RecordError{"colour is NaN or infinite"};
            mesh.colors.push_back(color);
        }
    }
}

// Faces of four or more corners, triangulated once every vertex is known (the face element may
// come first), and put in the file's order among the triangles.
struct PlyPolygons {
    struct Polygon {
        uint64_t record;       // its face, for messages
        uint64_t firstCorner;  // in corners
        uint64_t cornerCount;
        uint64_t beforeTriangle;  // the number of triangles read before it
    };
    std::vector<Polygon> polygons;
    std::vector<uint32_t> corners;
    uint64_t triangles = 0;   // at most, corners - 2 each: counted against the bound as read
    uint64_t shortFaces = 0;  // of fewer than 3 corners, skipped
};

// Reads the index list of each record of ELEMENT (its other properties skipped) and hands it to
// onList, checked against the vertex count; -1 passes where allowMinusOne (strip ends).
template <class Reader, class OnList>
void ReadPlyIndexLists(Reader& reader, const PlyElement& element, int listProperty,
                       int64_t vertexCount, bool allowMinusOne, uint64_t& record, OnList&& onList) {
    const PlyProperty& indexProperty = element.properties[listProperty];
    std::vector<int64_t> list;
    for (; record < element.count; ++record) {
        for (size_t i = 0; i < element.properties.size(); ++i) {
            if (static_cast<int>(i) != listProperty) {
                SkipProperty(reader, element.properties[i]);
                continue;
            }
            int64_t count = reader.ReadInteger(indexProperty.countType);
            if (count < 0) throw RecordError{"negative vertex count " + std::to_string(count)};
            list.clear();
            for (int64_t item = 0; item < count; ++item) {
                int64_t index = reader.ReadInteger(indexProperty.type);
                if ((index < 0 || index >= vertexCount) && !(allowMinusOne && index == -1)) {
                    throw RecordError{"vertex index " + std::to_string(index) + " out of range (" +
                                      std::to_string(vertexCount) + " vertices)"};
                }
                list.push_back(index);
            }
            onList(list);
        }
        reader.EndRecord();
    }
}

// PENDING: the triangles of polygons still to be split, which count against the bound too.
void AddTriangle(uint32_t a, uint32_t b, uint32_t c, TriangleMesh& mesh, uint64_t pending) {
    if (a == b || b == c || a == c) return;
    mesh_text::CheckTriangleCount(mesh.indices.size() + pending);
    mesh.indices.emplace_back(a, b, c);
}

template <class Reader>
void ReadPlyFaces(Reader& reader, const PlyLayout& layout, uint64_t& record, TriangleMesh& mesh,
                  PlyPolygons& pending) {
    ReadPlyIndexLists(
        reader, *layout.faces, layout.faceIndexProperty, int64_t(layout.vertices->count), false,
        record, [&](const std::vector<int64_t>& corners) {
            // A face of fewer corners (a loose edge) has no surface: skipped and counted for a
            // warning (it had been dropped without a word).
            if (corners.size() < 3) {
                ++pending.shortFaces;
                return;
            }
            if (corners.size() == 3) {
                AddTriangle(uint32_t(corners[0]), uint32_t(corners[1]), uint32_t(corners[2]), mesh,
                            pending.triangles);
                return;
            }
            // Kept without repeats in a row, which add nothing (a face of 255 copies of one
            // vertex is none): a polygon buffered costs what its distinct corners do.
            const uint64_t first = pending.corners.size();
            for (int64_t corner : corners)
                if (pending.corners.size() == first || pending.corners.back() != uint32_t(corner))
                    pending.corners.push_back(uint32_t(corner));
            while (pending.corners.size() - first > 1 &&
                   pending.corners.back() == pending.corners[first])
                pending.corners.pop_back();
            const uint64_t count = pending.corners.size() - first;
            if (count < 3) {
                pending.corners.resize(first);
                return;
            }
            pending.triangles += count - 2;
            mesh_text::CheckTriangleCount(mesh.indices.size() + pending.triangles - 1);
            pending.polygons.push_back({record, first, count, mesh.indices.size()});
        });
}

// Triangle strips: each triangle is the last three indices, every other one with its first two
// swapped so that all keep the strip's winding; -1 starts a new strip.
template <class Reader>
void ReadPlyStrips(Reader& reader, const PlyLayout& layout, uint64_t& record, TriangleMesh& mesh,
                   const PlyPolygons& pending) {
    ReadPlyIndexLists(reader, *layout.strips, layout.stripIndexProperty,
                      int64_t(layout.vertices->count), true, record,
                      [&](const std::vector<int64_t>& indices) {
                          size_t start = 0;
                          for (size_t i = 0; i < indices.size(); ++i) {
                              if (indices[i] < 0) {
                                  start = i + 1;
                                  continue;
                              }
                              if (i < start + 2) continue;
                              const auto a = uint32_t(indices[i - 2]), b = uint32_t(indices[i - 1]),
                                         c = uint32_t(indices[i]);
                              if ((i - start) % 2 == 0) {
                                  AddTriangle(a, b, c, mesh, pending.triangles);
                              } else {
                                  AddTriangle(b, a, c, mesh, pending.triangles);
                              }
                          }
                      });
}

// Puts the pending polygons' triangles among the others, in the file's order.
void TriangulatePolygons(const std::string& path, const PlyPolygons& pending, TriangleMesh& mesh) {
    if (pending.polygons.empty()) return;
    PolygonTriangulator triangulator;
    TriangleMesh merged;
    merged.positions = std::move(mesh.positions);
    merged.normals = std::move(mesh.normals);
    merged.colors = std::move(mesh.colors);
    merged.indices.reserve(mesh.indices.size() + pending.triangles);
    std::vector<vec3> positions;
    std::vector<glm::uvec3> local;
    size_t next = 0;
    for (const PlyPolygons::Polygon& polygon : pending.polygons) {
        while (next < polygon.beforeTriangle) merged.indices.push_back(mesh.indices[next++]);
        const uint32_t* corners = pending.corners.data() + polygon.firstCorner;
        positions.clear();
        for (uint64_t i = 0; i < polygon.cornerCount; ++i)
            positions.push_back(merged.positions[corners[i]]);
        local.clear();
        triangulator.Triangulate(positions, local);
        try {
            for (const glm::uvec3& t : local)
                AddTriangle(corners[t.x], corners[t.y], corners[t.z], merged, 0);
        } catch (const RecordError& error) {
            throw InputError(path, "face " + std::to_string(polygon.record), error.reason);
        }
    }
    while (next < mesh.indices.size()) merged.indices.push_back(mesh.indices[next++]);
    mesh = std::move(merged);
    mesh_text::WarnOfFannedPolygons(path, triangulator);
}

template <class Reader>
void ReadPlyBody(const std::string& path, const PlyHeader& header, const PlyLayout& layout,
                 size_t bodyBytes, Reader& reader, TriangleMesh& mesh) {
    PlyPolygons pending;
    mesh.positions.reserve(layout.vertices->count);
    if (layout.hasNormals) mesh.normals.reserve(layout.vertices->count);
    if (layout.hasColors) mesh.colors.reserve(layout.vertices->count);
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
                ReadPlyFaces(reader, layout, record, mesh, pending);
            } else if (&element == layout.strips) {
                ReadPlyStrips(reader, layout, record, mesh, pending);
            } else {
                for (; record < element.count; ++record) {
                    for (const PlyProperty& property : element.properties) {
                        SkipProperty(reader, property);
                    }
                    reader.EndRecord();
                }
            }
        } catch (const RecordError& error) {
            throw InputError(path, element.name + " " + std::to_string(record), error.reason);
        }
    }
    if (const std::optional<std::string> leftover = reader.Leftover()) {
        if (Reader::kLeftoverIsError) throw InputError(path, "", *leftover);
        std::fprintf(stderr, "rtrt: warning: %s: %s\n", WithoutControlCharacters(path).c_str(),
                     leftover->c_str());
    }
    TriangulatePolygons(path, pending, mesh);
    mesh_text::WarnOfShortFaces(path, pending.shortFaces);
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
    if (layout.hasNormals) {
        mesh_text::KeepFileNormals(mesh);
    } else {
        ComputeSmoothNormals(mesh);
    }
    mesh_text::ClampColors(path, mesh.colors);
    return mesh;
}

}  // namespace rtrt
