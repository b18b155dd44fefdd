#include "game/assets/teapot.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/geometry/smooth_normals.h"

namespace rtrt {
namespace {

constexpr size_t kPatchCount = 32;
constexpr size_t kPointsPerPatch = 16;
constexpr uintmax_t kMaxFileBytes = uintmax_t{16} << 20;

// Control point (row, column) is points[4 * row + column]; u runs along a row, v along a column.
using Patch = std::array<vec3, kPointsPerPatch>;

std::string ReadTextFile(const std::string& path) { return ReadAssetFile(path, kMaxFileBytes); }

// Blanks out // and /* */ comments and string literals, so that nothing inside them counts.
std::string BlankCommentsAndStrings(std::string text) {
    size_t i = 0;
    auto blankUntil = [&](size_t end) {
        end = std::min(end, text.size());
        for (; i < end; ++i) {
            if (text[i] != '\n') text[i] = ' ';
        }
    };
    while (i < text.size()) {
        if (text.compare(i, 2, "//") == 0) {
            blankUntil(text.find('\n', i));
        } else if (text.compare(i, 2, "/*") == 0) {
            size_t close = text.find("*/", i + 2);
            blankUntil(close == std::string::npos ? close : close + 2);
        } else if (text[i] == '"') {
            size_t close = text.find('"', i + 1);
            blankUntil(close == std::string::npos ? close : close + 1);
        } else {
            ++i;
        }
    }
    return text;
}

bool IsIdentifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::string_view Trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

bool ParseDouble(std::string_view token, double& value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    auto [next, ec] = std::from_chars(token.data(), end, value);
    return ec == std::errc() && next == end && std::isfinite(value);
}

// Parses "x, y, z" (the text between < and >) and turns the data's z-up frame (the teapot's
// height is z, 0 to 3.15) into rtrt's y-up one: a rotation by -90 degrees about x. POV-Ray's frame
// is left-handed, but the teapot is symmetric in the file's y, so no mirror is needed.
bool ParseControlPoint(std::string_view text, vec3& point) {
    std::array<double, 3> xyz{};
    for (size_t axis = 0; axis < 3; ++axis) {
        size_t comma = axis < 2 ? text.find(',') : std::string_view::npos;
        if (axis < 2 && comma == std::string_view::npos) return false;
        if (!ParseDouble(Trim(text.substr(0, comma)), xyz[axis])) return false;
        text.remove_prefix(comma == std::string_view::npos ? text.size() : comma + 1);
    }
    point =
        vec3(static_cast<float>(xyz[0]), static_cast<float>(xyz[2]), -static_cast<float>(xyz[1]));
    return std::isfinite(point.x) && std::isfinite(point.y) && std::isfinite(point.z);
}

// Reads the block that starts at code[at] with "{": the control points are the vectors directly
// inside it, except the four after uv_vectors; vectors in nested blocks (texture) do not count.
// at is left on the block's closing brace.
Patch ParsePatchBlock(const std::string& path, const std::string& field, std::string_view code,
                      size_t& at) {
    while (at < code.size() && std::isspace(static_cast<unsigned char>(code[at]))) ++at;
    if (at == code.size() || code[at] != '{') {
        throw InputError(path, field, "expected '{' after bicubic_patch");
    }
    Patch patch;
    size_t points = 0, uvVectorsLeft = 0;
    int depth = 0;
    for (; at < code.size(); ++at) {
        char c = code[at];
        if (c == '{') ++depth;
        if (c == '}' && --depth == 0) break;
        if (depth != 1) continue;
        if (IsIdentifierChar(c) && (at == 0 || !IsIdentifierChar(code[at - 1]))) {
            size_t end = at;
            while (end < code.size() && IsIdentifierChar(code[end])) ++end;
            if (code.substr(at, end - at) == "uv_vectors") uvVectorsLeft = 4;
            at = end - 1;
        } else if (c == '<') {
            size_t close = code.find('>', at);
            if (close == std::string_view::npos) break;
            std::string_view text = code.substr(at + 1, close - at - 1);
            at = close;
            if (uvVectorsLeft > 0) {
                --uvVectorsLeft;
                continue;
            }
            vec3 point;
            if (!ParseControlPoint(text, point)) {
                throw InputError(path, field,
                                 "control point " + std::to_string(points + 1) +
                                     " is not <x, y, z> with three finite numbers");
            }
            if (points < kPointsPerPatch) patch[points] = point;
            ++points;
        }
    }
    if (depth != 0) throw InputError(path, field, "unterminated bicubic_patch block");
    if (points != kPointsPerPatch) {
        throw InputError(path, field,
                         "expected 16 control points, found " + std::to_string(points));
    }
    return patch;
}

std::vector<Patch> ParsePatches(const std::string& path, const std::string& text) {
    std::string code = BlankCommentsAndStrings(text);
    constexpr std::string_view kKeyword = "bicubic_patch";
    std::vector<Patch> patches;
    for (size_t at = code.find(kKeyword); at != std::string::npos;
         at = code.find(kKeyword, at + 1)) {
        size_t end = at + kKeyword.size();
        if ((at > 0 && IsIdentifierChar(code[at - 1])) ||
            (end < code.size() && IsIdentifierChar(code[end]))) {
            continue;
        }
        std::string field = "patch " + std::to_string(patches.size() + 1);
        // The search goes on after the block: a keyword inside it is not parsed again.
        at = end;
        patches.push_back(ParsePatchBlock(path, field, code, at));
    }
    if (patches.size() != kPatchCount) {
        throw InputError(
            path, "", "expected 32 bicubic_patch blocks, found " + std::to_string(patches.size()));
    }
    return patches;
}

vec3 Lerp(vec3 a, vec3 b, float t) { return a + t * (b - a); }

// Point i / resolution of a cubic Bezier curve by de Casteljau. Where the four points are equal
// (a collapsed patch edge) every step returns them bit for bit. The curve is evaluated from its
// nearer end, and at t = 1/2 in the symmetric form (a + b) / 2, so that i = 0 and i = resolution
// give the end points exactly and two patches sharing an edge, running either way along it,
// compute the same bits there: the weld then closes every seam. (Always evaluating from p[0]
// leaves cracks: a + 1 * (b - a) need not round to b.)
vec3 EvaluateCurve(std::array<vec3, 4> p, int i, int resolution) {
    if (2 * i > resolution) {
        std::reverse(p.begin(), p.end());
        i = resolution - i;
    }
    bool midpoint = 2 * i == resolution;
    float t = static_cast<float>(i) / static_cast<float>(resolution);
    for (int level = 3; level > 0; --level) {
        for (int k = 0; k < level; ++k) {
            p[k] = midpoint ? 0.5f * (p[k] + p[k + 1]) : Lerp(p[k], p[k + 1], t);
        }
    }
    return p[0];
}

vec3 EvaluatePatch(const Patch& patch, int iu, int iv, int resolution) {
    std::array<vec3, 4> column;
    for (size_t row = 0; row < 4; ++row) {
        const vec3* p = &patch[4 * row];
        column[row] = EvaluateCurve({p[0], p[1], p[2], p[3]}, iu, resolution);
    }
    return EvaluateCurve(column, iv, resolution);
}

struct PositionHash {
    size_t operator()(const std::array<uint32_t, 3>& bits) const {
        uint64_t h = bits[0];
        h = h * 0x9E3779B97F4A7C15ull ^ bits[1];
        h = h * 0x9E3779B97F4A7C15ull ^ bits[2];
        return static_cast<size_t>(h ^ (h >> 29));
    }
};

class Welder {
  public:
    explicit Welder(TriangleMesh& mesh) : mesh_(mesh) {}

    uint32_t Vertex(vec3 p) {
        p += vec3(0.0f);  // -0 becomes +0, so that equal positions have equal bits
        std::array<uint32_t, 3> key = {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y),
                                       std::bit_cast<uint32_t>(p.z)};
        auto [it, inserted] =
            vertexOf_.try_emplace(key, static_cast<uint32_t>(mesh_.positions.size()));
        if (inserted) mesh_.positions.push_back(p);
        return it->second;
    }

  private:
    TriangleMesh& mesh_;
    std::unordered_map<std::array<uint32_t, 3>, uint32_t, PositionHash> vertexOf_;
};

void AddTriangle(TriangleMesh& mesh, uint32_t a, uint32_t b, uint32_t c) {
    if (a != b && b != c && a != c) mesh.indices.emplace_back(a, b, c);
}

TriangleMesh Tessellate(const std::vector<Patch>& patches, int resolution) {
    TriangleMesh mesh;
    Welder welder(mesh);
    int n = resolution + 1;
    std::vector<uint32_t> grid(static_cast<size_t>(n) * n);
    for (const Patch& patch : patches) {
        for (int iv = 0; iv <= resolution; ++iv) {
            for (int iu = 0; iu <= resolution; ++iu) {
                grid[iv * n + iu] = welder.Vertex(EvaluatePatch(patch, iu, iv, resolution));
            }
        }
        // Every patch of the data has dP/du x dP/dv pointing out of the teapot; the triangles
        // wind the same way, so their normals point out too.
        for (int iv = 0; iv < resolution; ++iv) {
            for (int iu = 0; iu < resolution; ++iu) {
                uint32_t p00 = grid[iv * n + iu], p10 = grid[iv * n + iu + 1];
                uint32_t p01 = grid[(iv + 1) * n + iu], p11 = grid[(iv + 1) * n + iu + 1];
                AddTriangle(mesh, p00, p10, p11);
                AddTriangle(mesh, p00, p11, p01);
            }
        }
    }
    return mesh;
}

}  // namespace

TriangleMesh TessellateTeapot(const std::string& teapotIncPath, int resolution) {
    if (resolution < 1 || resolution > kMaxTeapotResolution) {
        throw InputError(teapotIncPath, "resolution",
                         "must be in [1, " + std::to_string(kMaxTeapotResolution) + "], got " +
                             std::to_string(resolution));
    }
    std::vector<Patch> patches = ParsePatches(teapotIncPath, ReadTextFile(teapotIncPath));
    TriangleMesh mesh = Tessellate(patches, resolution);
    ComputeSmoothNormals(mesh);
    return mesh;
}

}  // namespace rtrt
