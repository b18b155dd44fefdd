#include "game/assets/obj_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/geometry/smooth_normals.h"
#include "game/assets/mesh_text.h"
#include "game/assets/polygon_triangulation.h"

namespace rtrt {
namespace {

using mesh_text::kMaxVertices;
using mesh_text::NextWord;
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

// A normal beyond float's range reads as infinite and, like a NaN one, takes the computed normal.
vec3 ParseObjVector(std::string_view rest, const char* what, bool normal) {
    vec3 v;
    for (int axis = 0; axis < 3; ++axis) {
        std::string_view word = NextWord(rest);
        if (word.empty()) throw RecordError{std::string(what) + " needs three coordinates"};
        v[axis] = ParseCoordinate(word, !normal);
    }
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
    // Per vertex once any vertex statement gives a colour; white for those that give none.
    std::vector<vec3> colors;
    uint64_t uncolored = 0;  // vertices given white so
    uint64_t oddExtras = 0;  // vertex statements with values past x y z that are no colour
    size_t texcoords = 0;
    std::vector<glm::uvec3> triangles;
    std::vector<glm::uvec3> normalTriangles;  // normal indices of the same corners
    bool anyCornerHasNormal = false;
    uint64_t shortFaces = 0;  // of fewer than 3 corners, skipped
    PolygonTriangulator triangulator;
    // The face being read, its corners' positions and its triangles as indices into it.
    std::vector<ObjCorner> face;
    std::vector<vec3> facePositions;
    std::vector<glm::uvec3> faceTriangles;
};

void ParseObjFace(std::string_view rest, ObjData& obj) {
    obj.face.clear();
    for (std::string_view word = NextWord(rest); !word.empty(); word = NextWord(rest)) {
        obj.face.push_back(
            ParseObjCorner(word, obj.positions.size(), obj.texcoords, obj.normals.size()));
        obj.anyCornerHasNormal |= obj.face.back().normal != kNoNormal;
    }
    // A face of fewer corners (a loose edge, as older exporters wrote them) has no surface: it is
    // skipped and counted for a warning (it had been dropped without a word).
    if (obj.face.size() < 3) {
        ++obj.shortFaces;
        return;
    }
    obj.faceTriangles.clear();
    if (obj.face.size() == 3) {
        obj.faceTriangles.emplace_back(0, 1, 2);
    } else if (obj.face.size() > 3) {
        obj.facePositions.clear();
        for (const ObjCorner& corner : obj.face)
            obj.facePositions.push_back(obj.positions[corner.vertex]);
        obj.triangulator.Triangulate(obj.facePositions, obj.faceTriangles);
    }
    for (const glm::uvec3& local : obj.faceTriangles) {
        const ObjCorner a = obj.face[local.x], b = obj.face[local.y], c = obj.face[local.z];
        if (a.vertex == b.vertex || b.vertex == c.vertex || a.vertex == c.vertex) continue;
        mesh_text::CheckTriangleCount(obj.triangles.size());
        obj.triangles.emplace_back(a.vertex, b.vertex, c.vertex);
        obj.normalTriangles.emplace_back(a.normal, b.normal, c.normal);
    }
}

// The colour a vertex statement gives after its coordinates (x y z r g b, as MeshLab and other
// tools write it), where exactly three numbers follow them. A fourth coordinate alone (w) is no
// colour; other values past x y z (which rtrt ignored before it read colours) are counted for a
// warning and ignored.
void ReadObjVertexColor(std::string_view rest, ObjData& obj) {
    for (int axis = 0; axis < 3; ++axis) NextWord(rest);
    std::array<std::string_view, 3> words;
    size_t count = 0;
    for (std::string_view word = NextWord(rest); !word.empty(); word = NextWord(rest))
        if (count++ < words.size()) words[count - 1] = word;
    // As doubles and bounded, so that a value beyond float's range is clamped like any above 1.
    vec3 color;
    bool numbers = count == 3;
    for (size_t k = 0; numbers && k < 3; ++k) {
        double value = 0.0;
        numbers = ParseNumber(words[k], value);
        color[int(k)] = float(std::clamp(value, -1.0, 2.0));
    }
    if (!numbers) {
        if (count > 1) ++obj.oddExtras;
        if (!obj.colors.empty()) {
            obj.colors.emplace_back(1.0f);
            ++obj.uncolored;
        }
        return;
    }
    if (std::isnan(color.x) || std::isnan(color.y) || std::isnan(color.z))
        throw RecordError{"vertex colour is NaN"};
    if (obj.colors.empty()) {
        obj.uncolored = obj.positions.size() - 1;
        obj.colors.assign(obj.uncolored, vec3(1.0f));
    }
    obj.colors.push_back(color);
}

void ParseObjLine(std::string_view line, ObjData& obj) {
    line = line.substr(0, line.find('#'));
    std::string_view keyword = NextWord(line);
    if (keyword.empty()) return;
    if (keyword == "v") {
        obj.positions.push_back(ParseObjVector(line, "vertex", false));
        if (!IsFinite(obj.positions.back())) {
            throw RecordError{"vertex coordinate is NaN or infinite"};
        }
        ReadObjVertexColor(line, obj);
        if (obj.positions.size() > kMaxVertices) throw RecordError{"too many vertices"};
    } else if (keyword == "vn") {
        obj.normals.push_back(ParseObjVector(line, "normal", true));
    } else if (keyword == "f") {
        ParseObjFace(line, obj);
    } else if (keyword == "vt") {
        ++obj.texcoords;
    } else if (std::find(kIgnoredObjStatements.begin(), kIgnoredObjStatements.end(), keyword) ==
               kIgnoredObjStatements.end()) {
        throw RecordError{"unknown statement " + Quote(keyword)};
    }
}

// Gives each distinct (vertex, normal) pair of the faces its own vertex. A corner without a
// normal, or whose normal has no direction, takes its vertex's area-weighted normal over every
// face around it.
TriangleMesh SplitByNormals(ObjData& obj) {
    bool everyCornerUsable = true;
    std::vector<bool> usable(obj.normals.size());
    for (size_t n = 0; n < obj.normals.size(); ++n)
        usable[n] = mesh_text::NormalizeFileNormal(obj.normals[n]);
    for (glm::uvec3& corners : obj.normalTriangles)
        for (int corner = 0; corner < 3; ++corner) {
            if (corners[corner] != kNoNormal && !usable[corners[corner]])
                corners[corner] = kNoNormal;
            everyCornerUsable &= corners[corner] != kNoNormal;
        }
    TriangleMesh smooth;
    if (!everyCornerUsable) {
        smooth.positions = obj.positions;
        smooth.indices = obj.triangles;
        ComputeSmoothNormals(smooth);
    }
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
                mesh.normals.push_back(n == kNoNormal ? smooth.normals[v] : obj.normals[n]);
                if (!obj.colors.empty()) mesh.colors.push_back(obj.colors[v]);
            }
            mesh.indices[t][corner] = it->second;
        }
    }
    return mesh;
}

// Whether LINE, comments aside, ends in a backslash: the OBJ statement goes on on the next line.
bool ContinuesOnNextLine(std::string_view line) {
    line = line.substr(0, line.find('#'));
    const size_t last = line.find_last_not_of(" \t");
    return last != std::string_view::npos && line[last] == '\\';
}

}  // namespace

TriangleMesh ParseObj(const std::string& path, std::string_view text, uint64_t* fileVertices) {
    ObjData obj;
    // A UTF-8 byte order mark, which some editors write first, is no part of the first line.
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
    size_t lineNumber = 0, statementLine = 0;
    std::string continued;  // a statement whose lines end in a backslash, joined so far
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
        if (continued.empty()) statementLine = lineNumber;
        if (ContinuesOnNextLine(line)) {
            line = line.substr(0, line.find('#'));
            continued.append(line.substr(0, line.find_last_of('\\'))).push_back(' ');
            if (!text.empty()) continue;
            line = {};
        }
        if (!continued.empty()) {
            continued.append(line);
            line = continued;
        }
        try {
            ParseObjLine(line, obj);
        } catch (const RecordError& error) {
            throw InputError(path, "line " + std::to_string(statementLine), error.reason);
        }
        continued.clear();
    }
    mesh_text::WarnOfFannedPolygons(path, obj.triangulator);
    mesh_text::WarnOfShortFaces(path, obj.shortFaces);
    if (fileVertices) *fileVertices = obj.positions.size();
    if (obj.oddExtras > 0)
        std::fprintf(stderr,
                     "rtrt: warning: %s: %llu vertex statements have values after x y z that are "
                     "not a colour (x y z r g b) or w; they are ignored\n",
                     WithoutControlCharacters(path).c_str(),
                     static_cast<unsigned long long>(obj.oddExtras));
    mesh_text::ClampColors(path, obj.colors);
    if (obj.uncolored > 0 && !obj.colors.empty())
        std::fprintf(stderr,
                     "rtrt: warning: %s: %llu vertices without a colour (x y z r g b) among "
                     "coloured ones are white\n",
                     WithoutControlCharacters(path).c_str(),
                     static_cast<unsigned long long>(obj.uncolored));
    TriangleMesh mesh;
    if (obj.anyCornerHasNormal && !obj.triangles.empty()) {
        mesh = SplitByNormals(obj);
    } else {
        mesh.positions = std::move(obj.positions);
        mesh.colors = std::move(obj.colors);
        mesh.indices = std::move(obj.triangles);
        ComputeSmoothNormals(mesh);
    }
    return mesh;
}

}  // namespace rtrt
