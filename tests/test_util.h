#pragma once
// Helpers shared by the test suites.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt::test {

inline std::string ModelDir() {
    if (const char* env = std::getenv("RTRT_MODEL_DIR"); env && *env) return env;
    return RTRT_TEST_MODEL_DIR;
}

// The path of a fetched model, or "" (the test then skips: run tools/fetch_models.sh).
inline std::string FetchedModel(const std::string& name) {
    const std::string path = ModelDir() + "/" + name;
    return std::filesystem::exists(path) ? path : std::string();
}

#define RTRT_REQUIRE_MODEL(var, name)                                 \
    const std::string var = ::rtrt::test::FetchedModel(name);         \
    if (var.empty())                                                  \
    GTEST_SKIP() << name << " is not in " << ::rtrt::test::ModelDir() \
                 << "; run tools/fetch_models.sh"

inline std::string SourcePath(const std::string& relative) {
    return std::string(RTRT_SOURCE_DIR) + "/" + relative;
}

// A soup of random triangles of varied size inside [-1, 1]^3.
inline TriangleMesh RandomTriangles(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f), size(0.002f, 0.2f);
    TriangleMesh mesh;
    for (uint32_t i = 0; i < count; ++i) {
        const vec3 c(pos(rng), pos(rng), pos(rng));
        const float s = size(rng);
        for (int k = 0; k < 3; ++k)
            mesh.positions.push_back(c + s * vec3(pos(rng), pos(rng), pos(rng)));
        mesh.indices.push_back({3 * i, 3 * i + 1, 3 * i + 2});
    }
    return mesh;
}

// n boxes with centres in [-spread, spread]^3 and half sizes in [0.01, 0.5].
inline std::vector<Aabb> RandomBoxes(uint32_t n, float spread, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-spread, spread), s(0.01f, 0.5f);
    std::vector<Aabb> boxes(n);
    for (Aabb& b : boxes) {
        const vec3 c(u(rng), u(rng), u(rng));
        b = {c - vec3(s(rng)), c + vec3(s(rng))};
    }
    return boxes;
}

// An n x n grid of quads in y = 0 spanning [-1, 1]^2: shared edges and vertices everywhere.
inline TriangleMesh GridMesh(uint32_t n) {
    TriangleMesh mesh;
    for (uint32_t j = 0; j <= n; ++j)
        for (uint32_t i = 0; i <= n; ++i)
            mesh.positions.push_back({-1.0f + 2.0f * i / n, 0.0f, -1.0f + 2.0f * j / n});
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            mesh.indices.push_back({a, c, b});
            mesh.indices.push_back({b, c, d});
        }
    return mesh;
}

}  // namespace rtrt::test
