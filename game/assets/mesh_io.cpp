#include "game/assets/mesh_io.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "engine/core/error.h"

namespace rtrt {
namespace {

// Largest file, after decompression, that the loaders read: bounds memory on hostile input.
constexpr size_t kMaxFileBytes = size_t{2} << 30;
constexpr uint64_t kMaxVertices = std::numeric_limits<uint32_t>::max();

// A problem inside one record (an OBJ line, a PLY element); the caller knows which record it is
// and rethrows it as an InputError.
struct RecordError {
    std::string reason;
};

bool EndsWith(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

std::string ToLower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool IsSpace(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

std::string Quote(std::string_view token) {
    constexpr size_t kMaxShown = 32;
    if (token.size() > kMaxShown) return "'" + std::string(token.substr(0, kMaxShown)) + "...'";
    return "'" + std::string(token) + "'";
}

// Parses all of TOKEN as a number; from_chars rejects the leading '+' that some writers emit.
template <class T>
bool ParseNumber(std::string_view token, T& value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    auto [next, ec] = std::from_chars(token.data(), end, value);
    return ec == std::errc() && next == end;
}

float ParseCoordinate(std::string_view token) {
    double value = 0.0;
    if (!ParseNumber(token, value)) throw RecordError{"expected a number, found " + Quote(token)};
    return static_cast<float>(value);
}

bool IsFinite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Normalises normals read from a file; false when one of them has no direction.
bool NormalizeFileNormals(std::vector<vec3>& normals) {
    for (vec3& n : normals) {
        float length = glm::length(n);
        if (!(length > 0.0f) || !std::isfinite(length)) return false;
        n /= length;
    }
    return true;
}

void CheckRegularFile(const std::string& path) {
    std::error_code ec;
    std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (ec) throw InputError(path, "", "cannot open file: " + ec.message());
    if (!std::filesystem::is_regular_file(status)) throw InputError(path, "", "not a regular file");
}

std::string ReadPlainFile(const std::string& path) {
    CheckRegularFile(path);
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
    std::error_code ec;
    uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(path, "", "cannot read file size: " + ec.message());
    if (size > kMaxFileBytes) throw InputError(path, "", "file is larger than 2 GiB");
    std::string data(size, '\0');
    size_t read = std::fread(data.data(), 1, data.size(), file.get());
    if (std::ferror(file.get())) {
        throw InputError(path, "", std::string("read error: ") + std::strerror(errno));
    }
    data.resize(read);
    return data;
}

std::string ReadGzipFile(const std::string& path) {
    CheckRegularFile(path);
    std::unique_ptr<gzFile_s, int (*)(gzFile)> file(gzopen(path.c_str(), "rb"), &gzclose);
    if (!file) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
    gzbuffer(file.get(), 1 << 18);
    if (gzdirect(file.get())) throw InputError(path, "", "not a gzip file (bad magic)");
    constexpr size_t kChunk = size_t{1} << 22;
    std::string data;
    size_t size = 0;
    for (;;) {
        if (size == kMaxFileBytes) throw InputError(path, "", "decompressed data exceed 2 GiB");
        if (data.size() - size < kChunk) {
            data.resize(std::min(kMaxFileBytes, std::max(2 * data.size(), size + kChunk)));
        }
        unsigned want = static_cast<unsigned>(std::min(data.size() - size, kChunk));
        int got = gzread(file.get(), data.data() + size, want);
        if (got <= 0) break;
        size += static_cast<size_t>(got);
    }
    int status = Z_OK;
    const char* message = gzerror(file.get(), &status);
    if (status != Z_OK) throw InputError(path, "", std::string("corrupt gzip data: ") + message);
    data.resize(size);
    return data;
}

// ---------------------------------------------------------------------------------------------
// Wavefront OBJ

// Statements of the OBJ specification that carry nothing a triangle mesh needs.
constexpr auto kIgnoredObjStatements = std::to_array<std::string_view>(
    {"vp",     "o",          "g",         "s",     "mg",     "usemtl",   "mtllib",
     "usemap", "maplib",     "l",         "p",     "cstype", "deg",      "bmat",
     "step",   "curv",       "curv2",     "surf",  "parm",   "trim",     "hole",
     "scrv",   "sp",         "end",       "con",   "bevel",  "c_interp", "d_interp",
     "lod",    "shadow_obj", "trace_obj", "ctech", "stech",  "call",     "csh"});

constexpr uint32_t kNoNormal = std::numeric_limits<uint32_t>::max();

struct ObjCorner {
    uint32_t vertex;
    uint32_t normal;  // kNoNormal when the corner has none
};

// Splits off the next whitespace-separated word of LINE.
std::string_view NextWord(std::string_view& line) {
    size_t start = 0;
    while (start < line.size() && IsSpace(line[start])) ++start;
    size_t end = start;
    while (end < line.size() && !IsSpace(line[end])) ++end;
    std::string_view word = line.substr(start, end - start);
    line.remove_prefix(end);
    return word;
}

vec3 ParseObjVector(std::string_view rest, const char* what) {
    vec3 v;
    for (int axis = 0; axis < 3; ++axis) {
        std::string_view word = NextWord(rest);
        if (word.empty()) throw RecordError{std::string(what) + " needs three coordinates"};
        v[axis] = ParseCoordinate(word);
    }
    if (!IsFinite(v)) throw RecordError{std::string(what) + " coordinate is NaN or infinite"};
    return v;
}

// OBJ indices start at 1; negative ones count back from the last element defined so far.
uint32_t ResolveObjIndex(std::string_view token, size_t defined, const char* what) {
    int64_t index = 0;
    if (!ParseNumber(token, index)) {
        throw RecordError{std::string("bad ") + what + " index " + Quote(token)};
    }
    int64_t count = static_cast<int64_t>(defined);
    if (index > 0 && index <= count) return static_cast<uint32_t>(index - 1);
    if (index < 0 && index >= -count) return static_cast<uint32_t>(count + index);
    throw RecordError{std::string(what) + " index " + std::to_string(index) + " out of range (" +
                      std::to_string(defined) + " defined so far)"};
}

// A face corner reads v, v/vt, v//vn or v/vt/vn; the texture index is checked, then ignored.
ObjCorner ParseObjCorner(std::string_view word, size_t positions, size_t texcoords,
                         size_t normals) {
    std::array<std::string_view, 3> fields;
    size_t count = 0;
    for (;;) {
        size_t slash = word.find('/');
        if (count == 2 && slash != std::string_view::npos) {
            throw RecordError{"bad face corner " + Quote(word)};
        }
        fields[count++] = word.substr(0, slash);
        if (slash == std::string_view::npos) break;
        word.remove_prefix(slash + 1);
    }
    ObjCorner corner{ResolveObjIndex(fields[0], positions, "vertex"), kNoNormal};
    if (count >= 2 && !fields[1].empty()) ResolveObjIndex(fields[1], texcoords, "texture");
    if (count == 3) corner.normal = ResolveObjIndex(fields[2], normals, "normal");
    return corner;
}

struct ObjData {
    std::vector<vec3> positions;
    std::vector<vec3> normals;
    size_t texcoords = 0;
    std::vector<glm::uvec3> triangles;
    std::vector<glm::uvec3> normalTriangles;  // normal indices of the same corners
    bool everyCornerHasNormal = true;
};

void ParseObjFace(std::string_view rest, ObjData& obj) {
    ObjCorner first{}, previous{};
    size_t corners = 0;
    for (std::string_view word = NextWord(rest); !word.empty(); word = NextWord(rest), ++corners) {
        ObjCorner corner =
            ParseObjCorner(word, obj.positions.size(), obj.texcoords, obj.normals.size());
        if (corner.normal == kNoNormal) obj.everyCornerHasNormal = false;
        if (corners == 0) first = corner;
        bool distinct = first.vertex != previous.vertex && previous.vertex != corner.vertex &&
                        first.vertex != corner.vertex;
        if (corners >= 2 && distinct) {
            obj.triangles.emplace_back(first.vertex, previous.vertex, corner.vertex);
            obj.normalTriangles.emplace_back(first.normal, previous.normal, corner.normal);
        }
        previous = corner;
    }
}

void ParseObjLine(std::string_view line, ObjData& obj) {
    line = line.substr(0, line.find('#'));
    std::string_view keyword = NextWord(line);
    if (keyword.empty()) return;
    if (keyword == "v") {
        obj.positions.push_back(ParseObjVector(line, "vertex"));
        if (obj.positions.size() > kMaxVertices) throw RecordError{"too many vertices"};
    } else if (keyword == "vn") {
        obj.normals.push_back(ParseObjVector(line, "normal"));
    } else if (keyword == "f") {
        ParseObjFace(line, obj);
    } else if (keyword == "vt") {
        ++obj.texcoords;
    } else if (std::find(kIgnoredObjStatements.begin(), kIgnoredObjStatements.end(), keyword) ==
               kIgnoredObjStatements.end()) {
        throw RecordError{"unknown statement " + Quote(keyword)};
    }
}

// Gives each distinct (vertex, normal) pair of the faces its own vertex.
TriangleMesh SplitByNormals(const ObjData& obj) {
    TriangleMesh mesh;
    std::unordered_map<uint64_t, uint32_t> vertexOf;
    vertexOf.reserve(obj.positions.size());
    mesh.indices.resize(obj.triangles.size());
    for (size_t t = 0; t < obj.triangles.size(); ++t) {
        for (int corner = 0; corner < 3; ++corner) {
            uint32_t v = obj.triangles[t][corner], n = obj.normalTriangles[t][corner];
            uint64_t key = (uint64_t{v} << 32) | n;
            auto [it, inserted] =
                vertexOf.try_emplace(key, static_cast<uint32_t>(mesh.positions.size()));
            if (inserted) {
                mesh.positions.push_back(obj.positions[v]);
                mesh.normals.push_back(obj.normals[n]);
            }
            mesh.indices[t][corner] = it->second;
        }
    }
    return mesh;
}

TriangleMesh ParseObj(const std::string& path, std::string_view text) {
    ObjData obj;
    size_t lineNumber = 0;
    while (!text.empty()) {
        ++lineNumber;
        size_t newline = text.find('\n');
        std::string_view line = text.substr(0, newline);
        text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
        try {
            ParseObjLine(line, obj);
        } catch (const RecordError& error) {
            throw InputError(path, "line " + std::to_string(lineNumber), error.reason);
        }
    }
    if (obj.everyCornerHasNormal && !obj.triangles.empty()) {
        TriangleMesh mesh = SplitByNormals(obj);
        if (NormalizeFileNormals(mesh.normals)) return mesh;
    }
    TriangleMesh mesh;
    mesh.positions = std::move(obj.positions);
    mesh.indices = std::move(obj.triangles);
    ComputeSmoothNormals(mesh);
    return mesh;
}

// ---------------------------------------------------------------------------------------------
// Stanford PLY (Turk 1994): a text header of elements and typed properties, then the data.

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
    PlyHeader header;
    bool haveFormat = false;
    size_t offset = 0;
    for (size_t lineNumber = 1;; ++lineNumber) {
        size_t newline = data.find('\n', offset);
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
                    mesh.indices.emplace_back(first, previous, current);
                }
                previous = current;
            }
        }
    }
}

template <class Reader>
void ReadPlyBody(const std::string& path, const PlyHeader& header, const PlyLayout& layout,
                 Reader& reader, TriangleMesh& mesh) {
    mesh.positions.reserve(layout.vertices->count);
    if (layout.hasNormals) mesh.normals.reserve(layout.vertices->count);
    if (layout.faces) mesh.indices.reserve(layout.faces->count);
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

TriangleMesh ParsePly(const std::string& path, std::string_view data) {
    PlyHeader header = ParsePlyHeaderLines(path, data);
    data.remove_prefix(header.dataOffset);
    CheckPlyCounts(path, header, data.size());
    PlyLayout layout = FindPlyLayout(path, header);
    TriangleMesh mesh;
    if (header.format == PlyFormat::kAscii) {
        AsciiReader reader(data);
        ReadPlyBody(path, header, layout, reader, mesh);
    } else {
        bool bigEndianData = header.format == PlyFormat::kBinaryBigEndian;
        BinaryReader reader(data, bigEndianData != (std::endian::native == std::endian::big));
        ReadPlyBody(path, header, layout, reader, mesh);
    }
    if (!layout.hasNormals || !NormalizeFileNormals(mesh.normals)) ComputeSmoothNormals(mesh);
    return mesh;
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
