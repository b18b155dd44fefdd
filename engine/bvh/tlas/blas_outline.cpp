#include "engine/bvh/tlas/blas_outline.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace rtrt {
namespace {

// Whether the parts' images take less room than the turned box, on average over turns about a
// spread of axes by a spread of angles (a box's faces, for one, reach its corners whatever the
// turn, and would cost every TLAS build their transforms for nothing).
bool PartsSaveRoom(const BlasOutline& outline, const Aabb& box) {
    constexpr int kTurns = 32;
    constexpr double kKeepBelow = 0.97;
    double corners = 0.0, parts = 0.0;
    for (int k = 0; k < kTurns; ++k) {
        // Axes on a Fibonacci spiral over the sphere, angles the golden angle apart.
        const float z = 1.0f - (2.0f * float(k) + 1.0f) / float(kTurns);
        const float r = std::sqrt(1.0f - z * z), phi = 2.39996323f * float(k);
        const vec3 axis(r * std::cos(phi), r * std::sin(phi), z);
        const Affine m =
            AffineFromMat4(glm::rotate(glm::mat4(1.0f), 2.39996323f * float(k + 1), axis));
        corners += TransformBounds(m, box).Area();
        parts += PartsImageBox(m, outline, box).Area();
    }
    return parts < kKeepBelow * corners;
}

}  // namespace

vec4 BlasSphere(const Blas& blas) {
    if (blas.kind != GeometryKind::kSpheres || blas.spheres.size() != 1) return vec4(0.0f);
    const Sphere& s = blas.spheres[0];
    return vec4(s.center, s.radius);
}

BlasOutline OutlineOfBlas(const Blas& blas, bool deforms) {
    BlasOutline outline;
    outline.sphere = BlasSphere(blas);
    if (deforms || blas.nodes.empty() || blas.nodes[0].IsLeaf()) return outline;
    std::vector<uint32_t> parts{0};
    while (parts.size() < BlasOutline::kMaxParts) {
        // The interior node of largest surface area, split into its two children.
        auto widest = parts.end();
        for (auto it = parts.begin(); it != parts.end(); ++it) {
            const BvhNode& node = blas.nodes[*it];
            if (!node.IsLeaf() && (widest == parts.end() ||
                                   node.Bounds().Area() > blas.nodes[*widest].Bounds().Area()))
                widest = it;
        }
        if (widest == parts.end()) break;
        const uint32_t left = blas.nodes[*widest].leftFirst;
        *widest = left;
        parts.push_back(left + 1);
    }
    for (uint32_t index : parts) {
        const Aabb box = blas.nodes[index].Bounds();
        if (box.IsEmpty()) continue;  // holds nothing
        const vec3 centre = 0.5f * (box.min + box.max);
        vec3 half;
        for (int i = 0; i < 3; ++i)
            half[i] = NextFloatUp(std::max(box.max[i] - centre[i], centre[i] - box.min[i]));
        outline.partCentre[outline.partCount] = centre;
        outline.partHalf[outline.partCount] = half;
        ++outline.partCount;
    }
    if (outline.partCount > 0 && !PartsSaveRoom(outline, blas.bounds)) outline.partCount = 0;
    return outline;
}

std::vector<BlasOutline> BlasOutlines(std::span<const std::shared_ptr<const Blas>> blases) {
    std::vector<BlasOutline> outlines;
    outlines.reserve(blases.size());
    for (const auto& blas : blases) outlines.push_back(OutlineOfBlas(*blas));
    return outlines;
}

}  // namespace rtrt
