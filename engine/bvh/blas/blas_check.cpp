#include "engine/bvh/blas/blas_check.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <vector>

#include "engine/core/error.h"

namespace rtrt {
namespace {

std::string Indexed(const char* array, size_t i) {
    return std::string(array) + "[" + std::to_string(i) + "]";
}

bool Finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool Finite2(vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

bool ProperBox(vec3 lo, vec3 hi) {
    return Finite(lo) && Finite(hi) && lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z;
}

class Checker {
  public:
    Checker(const Blas& blas, const std::string& file, bool repeatedIds)
        : blas_(blas), file_(file), repeatedIds_(repeatedIds) {}

    void Run() {
        CheckSizes();
        // The checks are independent and run in parallel; when several fail, the first in this
        // order is reported, so a file always gets the same message.
        std::exception_ptr failures[4];
        auto guarded = [&](int i, auto check) {
            return [&failures, i, check] {
                try {
                    check();
                } catch (...) {
                    failures[i] = std::current_exception();
                }
            };
        };
        tbb::parallel_invoke(guarded(0, [&] { CheckBinaryTree(); }),
                             guarded(1,
                                     [&] {
                                         if (!blas_.nodes4.empty()) CheckWideTree();
                                     }),
                             guarded(2, [&] { CheckPrimIds(); }),
                             guarded(3, [&] { CheckGeometry(); }));
        for (const std::exception_ptr& failure : failures)
            if (failure) std::rethrow_exception(failure);
    }

  private:
    [[noreturn]] void Fail(const std::string& field, const std::string& reason) const {
        throw InputError(file_, field, reason);
    }

    void CheckSizes() const {
        const size_t prims = blas_.primIds.size();
        if (prims == 0) Fail("primIds", "the model has no primitives");
        if (blas_.nodes.size() < 2) Fail("nodes", "fewer than 2 nodes (root and the unused slot)");
        if (blas_.kind == GeometryKind::kTriangles) {
            if (blas_.triangles.size() != prims)
                Fail("triangles", std::to_string(blas_.triangles.size()) + " triangles but " +
                                      std::to_string(prims) + " primIds");
            if (!blas_.normals.empty() && blas_.normals.size() != prims)
                Fail("normals", "expected 0 or " + std::to_string(prims) + " normal triples, got " +
                                    std::to_string(blas_.normals.size()));
            if (!blas_.uvs.empty() && blas_.uvs.size() != prims)
                Fail("uvs", "expected 0 or " + std::to_string(prims) + " uv triples, got " +
                                std::to_string(blas_.uvs.size()));
            if (!blas_.colors.empty() && blas_.colors.size() != prims)
                Fail("colors", "expected 0 or " + std::to_string(prims) + " colour triples, got " +
                                   std::to_string(blas_.colors.size()));
            if (!blas_.spheres.empty()) Fail("spheres", "a triangle model holds no spheres");
        } else if (blas_.kind == GeometryKind::kSpheres) {
            if (blas_.spheres.size() != prims)
                Fail("spheres", std::to_string(blas_.spheres.size()) + " spheres but " +
                                    std::to_string(prims) + " primIds");
            if (!blas_.triangles.empty() || !blas_.normals.empty() || !blas_.nodes4.empty() ||
                !blas_.uvs.empty() || !blas_.colors.empty())
                Fail("kind",
                     "a sphere model holds no triangles, normals, uvs, colours or 4-wide nodes");
        } else {
            Fail("kind", "unknown geometry kind " + std::to_string(uint32_t(blas_.kind)));
        }
    }

    // A leaf range [first, first + count) inside the primitives, without overflow.
    template <typename Field>
    void CheckLeafRange(const Field& field, uint64_t first, uint64_t count) const {
        const uint64_t prims = blas_.primIds.size();
        if (first > prims || count > prims - first)
            Fail(field(), "leaf primitives [" + std::to_string(first) + ", " +
                              std::to_string(first + count) + ") out of range (" +
                              std::to_string(prims) + " primitives)");
    }

    // Children must lie after their parent (so there are no cycles) and inside the array, and
    // no node may be reached twice (so the tree is a tree and visits are bounded).
    template <typename Field>
    void Visit(std::vector<uint8_t>& seen, const char* array, size_t parent, uint64_t child,
               size_t size, const Field& field) const {
        if (child <= parent || child >= size)
            Fail(field(), "child index " + std::to_string(child) + " out of range (node " +
                              std::to_string(parent) + " of " + std::to_string(size) + ")");
        if (seen[child]) Fail(Indexed(array, child), "node reached from two parents");
        seen[child] = 1;
    }

    void CheckBinaryTree() const {
        const auto& nodes = blas_.nodes;
        std::vector<uint8_t> seen(nodes.size(), 0);
        struct Item {
            uint32_t index, depth;
        };
        std::vector<Item> stack{{0, 0}};
        seen[0] = 1;
        while (!stack.empty()) {
            const Item item = stack.back();
            stack.pop_back();
            const BvhNode& node = nodes[item.index];
            // Field names are composed only on failure: this loop runs once per node.
            auto field = [&] { return Indexed("nodes", item.index); };
            if (!ProperBox(node.boundsMin, node.boundsMax))
                Fail(field(), "bounds are not finite or min > max");
            if (item.depth > kMaxBvhDepth)
                Fail(field(), "tree deeper than " + std::to_string(kMaxBvhDepth));
            if (node.IsLeaf()) {
                CheckLeafRange(field, node.leftFirst, node.primCount);
                continue;
            }
            // Children sit in pairs from index 2 (bvh_node.h), a line each, as every builder of
            // the engine lays them out.
            if (node.leftFirst % 2 != 0)
                Fail(field() + ".leftFirst", "child pair at odd index " +
                                                 std::to_string(node.leftFirst) +
                                                 " (pairs start at even indices from 2)");
            for (uint64_t c = node.leftFirst; c <= uint64_t(node.leftFirst) + 1; ++c) {
                Visit(seen, "nodes", item.index, c, nodes.size(),
                      [&] { return field() + ".leftFirst"; });
                stack.push_back({uint32_t(c), item.depth + 1});
            }
        }
        // Refits and SAH sums run over every node by index, not from the root: a node nothing
        // links to would be read as a leaf of whatever range it holds.
        for (size_t i = 2; i < nodes.size(); ++i)
            if (!seen[i])
                Fail(Indexed("nodes", i),
                     "no node links to it (every node but slot 1 is reached from the root)");
    }

    void CheckWideTree() const {
        const auto& nodes = blas_.nodes4;
        std::vector<uint8_t> seen(nodes.size(), 0);
        struct Item {
            uint32_t index, depth;
        };
        std::vector<Item> stack{{0, 0}};
        seen[0] = 1;
        while (!stack.empty()) {
            const Item item = stack.back();
            stack.pop_back();
            const Bvh4Node& node = nodes[item.index];
            if (item.depth > kMaxBvhDepth)
                Fail(Indexed("nodes4", item.index),
                     "tree deeper than " + std::to_string(kMaxBvhDepth));
            for (int i = 0; i < 4; ++i) {
                auto field = [&] {
                    return Indexed("nodes4", item.index) + ".child[" + std::to_string(i) + "]";
                };
                const vec3 lo(node.minX[i], node.minY[i], node.minZ[i]);
                const vec3 hi(node.maxX[i], node.maxY[i], node.maxZ[i]);
                if (node.count[i] == 0 && node.child[i] == 0) {
                    // An unused slot: its box must be the empty one so that no ray enters it.
                    if (lo != vec3(kInfinity) || hi != vec3(-kInfinity))
                        Fail(field(), "unused slot without the empty box");
                    continue;
                }
                if (!ProperBox(lo, hi)) Fail(field(), "bounds are not finite or min > max");
                if (node.count[i] > 0) {
                    CheckLeafRange(field, node.child[i], node.count[i]);
                    continue;
                }
                Visit(seen, "nodes4", item.index, node.child[i], nodes.size(), field);
                stack.push_back({node.child[i], item.depth + 1});
            }
        }
    }

    void CheckPrimIds() const {
        // Only triangles are split spatially.
        const bool repeated = repeatedIds_ && blas_.kind == GeometryKind::kTriangles;
        std::vector<uint8_t> seen(blas_.primIds.size(), 0);
        uint32_t sourceCount = 0;
        for (size_t slot = 0; slot < blas_.primIds.size(); ++slot) {
            const uint32_t id = blas_.primIds[slot];
            if (id >= seen.size())
                Fail(Indexed("primIds", slot), "primitive index " + std::to_string(id) +
                                                   " out of range (" + std::to_string(seen.size()) +
                                                   " primitives)");
            if (seen[id] && !repeated)
                Fail(Indexed("primIds", slot), "primitive " + std::to_string(id) + " listed twice");
            seen[id] = 1;
            sourceCount = std::max(sourceCount, id + 1);
        }
        // Repeated or not, the ids name every source primitive from 0 up.
        for (uint32_t id = 0; id < sourceCount; ++id)
            if (!seen[id])
                Fail("primIds", "primitive " + std::to_string(id) + " is in no leaf slot (" +
                                    std::to_string(sourceCount) + " primitives)");
    }

    void CheckGeometry() const {
        for (size_t i = 0; i < blas_.triangles.size(); ++i) {
            const Triangle& t = blas_.triangles[i];
            if (!Finite(t.v0) || !Finite(t.v1) || !Finite(t.v2))
                Fail(Indexed("triangles", i), "vertex coordinate is NaN or infinite");
        }
        // Packed normals need no check: every 32-bit pattern decodes to a unit vector.
        for (size_t i = 0; i < blas_.uvs.size(); ++i) {
            const TriangleUvs& t = blas_.uvs[i];
            if (!Finite2(t.uv0) || !Finite2(t.uv1) || !Finite2(t.uv2))
                Fail(Indexed("uvs", i), "texture coordinate is NaN or infinite");
        }
        for (size_t i = 0; i < blas_.spheres.size(); ++i) {
            const Sphere& s = blas_.spheres[i];
            if (!Finite(s.center) || !std::isfinite(s.radius) || s.radius < 0.0f)
                Fail(Indexed("spheres", i), "centre or radius is NaN, infinite or negative");
        }
    }

    const Blas& blas_;
    const std::string& file_;
    bool repeatedIds_;
};

}  // namespace

void CheckBlas(const Blas& blas, const std::string& file, bool repeatedIds) {
    Checker(blas, file, repeatedIds).Run();
}

}  // namespace rtrt
