#include "game/assets/obj_reader.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/geometry/smooth_normals.h"
#include "game/assets/mesh_text.h"

namespace rtrt {
namespace {

using mesh_text::kMaxVertices;
using mesh_text::NextWord;
using mesh_text::NormalizeFileNormals;
using mesh_text::ParseCoordinate;
using mesh_text::ParseNumber;
using mesh_text::Quote;
using mesh_text::RecordError;

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
            mesh_text::CheckTriangleCount(obj.triangles.size());
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

}  // namespace

TriangleMesh ParseObj(const std::string& path, std::string_view text) {
    ObjData obj;
    // A UTF-8 byte order mark, which some editors write first, is no part of the first line.
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
    size_t lineNumber = 0;
    while (!text.empty()) {
        ++lineNumber;
        // LF, CRLF, and a lone CR (old Mac files, whose lines were otherwise one).
        const size_t end = text.find_first_of("\r\n");
        std::string_view line = text.substr(0, end);
        size_t next = end == std::string_view::npos ? text.size() : end + 1;
        if (end != std::string_view::npos && text[end] == '\r' && next < text.size() &&
            text[next] == '\n')
            ++next;
        text.remove_prefix(next);
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

}  // namespace rtrt
