// The GPU TLAS equals the CPU's LBVH TLAS over the same records (placed so that both compute the
// same world boxes), bit for bit, built and refit, for 0 to 200,000 instances; it keeps nothing but
// its nodes (two per instance) on the device, and a refit after records were rewritten by their
// placement alone equals a CPU refit. Label gpu.
#include "engine/bvh/tlas/gpu_tlas.h"

#include <gtest/gtest.h>

#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "engine/bvh/build/lbvh.h"
#include "engine/render_rt/renderer.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

const std::vector<Aabb> kBlasBounds = {{vec3(-1.0f), vec3(1.0f)},
                                       {vec3(-0.5f, 0.0f, -2.0f), vec3(0.5f, 3.0f, 2.0f)}};

// A random translation, a rotation by a multiple of 90 degrees about an axis and a scale of 1/2,
// 1 or 2: the world boxes then come out the same on the host and on the device, whatever either
// compiler contracts into fused multiply-adds, so the trees can be compared bit for bit.
glm::mat4 RandomPlacement(std::mt19937& rng, float extent) {
    std::uniform_real_distribution<float> at(-extent, extent);
    std::uniform_int_distribution<int> pick(0, 2), quarter(0, 3);
    const float scales[3] = {0.5f, 1.0f, 2.0f};
    glm::mat4 m = glm::translate(glm::mat4(1.0f), vec3(at(rng), at(rng), at(rng)));
    glm::mat4 r(0.0f);
    const int axis = pick(rng), turns = quarter(rng);
    // The rotation's matrix written out, exact (glm::rotate's cosines of multiples of pi/2 are
    // not exactly 0).
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const float c[4] = {1, 0, -1, 0}, s[4] = {0, 1, 0, -1};
    r[axis][axis] = 1.0f;
    r[u][u] = c[turns];
    r[u][v] = s[turns];
    r[v][u] = -s[turns];
    r[v][v] = c[turns];
    r[3][3] = 1.0f;
    return glm::scale(m * r, vec3(scales[pick(rng)]));
}

std::vector<Instance> RandomInstances(uint32_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<Instance> instances;
    for (uint32_t i = 0; i < n; ++i)
        instances.push_back(MakeInstance(i % 2, 0, RandomPlacement(rng, 50.0f)));
    return instances;
}

void ExpectSameNodes(const AlignedVector<BvhNode>& cpu, const AlignedVector<BvhNode>& gpu) {
    ASSERT_EQ(cpu.size(), gpu.size());
    for (size_t i = 0; i < cpu.size(); ++i)
        ASSERT_EQ(std::memcmp(&cpu[i], &gpu[i], sizeof(BvhNode)), 0) << "node " << i;
}

TEST(GpuTlas, EqualsCpuForManySizes) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const DeviceBuffer<Aabb> blasBounds{std::span<const Aabb>(kBlasBounds)};
    for (uint32_t n : {0u, 1u, 2u, 3u, 17u, 1000u, 200000u}) {
        SCOPED_TRACE(n);
        const std::vector<Instance> instances = RandomInstances(n, n + 5);
        DeviceBuffer<Instance> records{std::span<const Instance>(instances)};
        GpuTlas gpu;
        gpu.Build(records.Data(), blasBounds.Data(), n);
        const Tlas cpu = BuildTlas(instances, kBlasBounds, TlasBuilder::kLbvh);
        ExpectSameNodes(cpu.nodes, gpu.Download().nodes);
    }
}

// Builds and refits over records with outlines (blas_outline.h) as the GPU and the host read them,
// compared bit for bit; a third of the records move before the refit.
void ExpectSameTreesWithOutlines(const std::vector<Aabb>& bounds,
                                 const std::vector<BlasOutline>& outlines) {
    const DeviceBuffer<Aabb> blasBounds{std::span<const Aabb>(bounds)};
    const DeviceBuffer<BlasOutline> blasOutlines{std::span<const BlasOutline>(outlines)};
    for (uint32_t n : {1u, 17u, 5000u}) {
        SCOPED_TRACE(n);
        std::vector<Instance> instances = RandomInstances(n, n + 11);
        DeviceBuffer<Instance> records{std::span<const Instance>(instances)};
        GpuTlas gpu;
        gpu.Build(records.Data(), {blasBounds.Data(), blasOutlines.Data()}, n);
        const Tlas cpu = BuildTlas(instances, bounds, TlasBuilder::kLbvh, outlines);
        ExpectSameNodes(cpu.nodes, gpu.Download().nodes);
        // A refit after a third of the instances moved takes their new boxes as the host's refit
        // does (unmoved, a refit that did nothing would pass too).
        Lbvh cpuLbvh =
            BuildLbvh(InstanceWorldBounds(instances, bounds, outlines), LbvhLeaves::kPrimitiveIds);
        std::vector<Instance> onDevice(n);
        records.Download(onDevice);
        std::mt19937 rng(n);
        for (uint32_t i = 0; i < n; ++i) {
            if (i % 3 == 0) SetTransform(instances[i], RandomPlacement(rng, 60.0f));
            SetPlacement(onDevice[i], instances[i]);
        }
        records.Upload(onDevice);
        gpu.Refit(records.Data(), {blasBounds.Data(), blasOutlines.Data()});
        RefitLbvh(cpuLbvh, InstanceWorldBounds(instances, bounds, outlines));
        ExpectSameNodes(cpuLbvh.nodes, gpu.Download().nodes);
        EXPECT_NE(
            std::memcmp(cpu.nodes.data(), cpuLbvh.nodes.data(), cpu.nodes.size() * sizeof(BvhNode)),
            0)
            << "the moves changed no box";
    }
}

// With a sphere inside BLAS 0's box (smaller than the box, so that the sphere's box is the
// tighter one): its instances' boxes come from the sphere on both sides, and the trees still
// match.
TEST(GpuTlas, EqualsCpuWithSphereBounds) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    std::vector<BlasOutline> outlines(2);
    outlines[0].sphere = vec4(0.25f, 0.0f, 0.0f, 0.5f);
    ExpectSameTreesWithOutlines(kBlasBounds, outlines);
}

// With the parts of two triangle BLASes (PartsImageBox), which the exact placements make the
// host and the device compute alike.
TEST(GpuTlas, EqualsCpuWithBlasParts) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const Blas a = BuildTriangleBlas(test::RandomTriangles(300, 4));
    const Blas b = BuildTriangleBlas(test::RandomTriangles(40, 5));
    const std::vector<BlasOutline> outlines = {OutlineOfBlas(a), OutlineOfBlas(b)};
    ASSERT_EQ(outlines[0].partCount, BlasOutline::kMaxParts);
    ExpectSameTreesWithOutlines({a.bounds, b.bounds}, outlines);
}

TEST(GpuTlas, KeepsOnlyItsNodes) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const DeviceBuffer<Aabb> blasBounds{std::span<const Aabb>(kBlasBounds)};
    for (uint32_t n : {1000u, 100000u}) {
        const std::vector<Instance> instances = RandomInstances(n, 9);
        DeviceBuffer<Instance> records{std::span<const Instance>(instances)};
        GpuTlas gpu;
        gpu.Build(records.Data(), blasBounds.Data(), n);
        EXPECT_EQ(gpu.DeviceBytes(), 2 * size_t(n) * sizeof(BvhNode)) << n << " instances";
    }
}

TEST(GpuTlas, EqualsCpuWithAllAtOnePoint) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const DeviceBuffer<Aabb> blasBounds{std::span<const Aabb>(kBlasBounds)};
    const std::vector<Instance> instances(5000, MakeInstance(1, 0, glm::mat4(1.0f)));
    DeviceBuffer<Instance> records{std::span<const Instance>(instances)};
    GpuTlas gpu;
    gpu.Build(records.Data(), blasBounds.Data(), uint32_t(instances.size()));
    ExpectSameNodes(BuildTlas(instances, kBlasBounds, TlasBuilder::kLbvh).nodes,
                    gpu.Download().nodes);
}

// As the runtime refits: the records' placements change on the device (SetPlacement, which
// leaves the TLAS words), then the same tree takes the new boxes.
TEST(GpuTlas, RefitEqualsCpuRefit) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const DeviceBuffer<Aabb> blasBounds{std::span<const Aabb>(kBlasBounds)};
    for (uint32_t n : {1u, 2u, 20000u}) {
        SCOPED_TRACE(n);
        std::vector<Instance> instances = RandomInstances(n, 3);
        DeviceBuffer<Instance> records{std::span<const Instance>(instances)};
        GpuTlas gpu;
        gpu.Build(records.Data(), blasBounds.Data(), n);
        Lbvh cpu =
            BuildLbvh(InstanceWorldBounds(instances, kBlasBounds), LbvhLeaves::kPrimitiveIds);

        std::vector<Instance> onDevice(n);
        records.Download(onDevice);
        std::mt19937 rng(77);
        for (uint32_t i = 0; i < n; ++i) {
            if (i % 3 == 0) SetTransform(instances[i], RandomPlacement(rng, 60.0f));
            SetPlacement(onDevice[i], instances[i]);
        }
        records.Upload(onDevice);
        gpu.Refit(records.Data(), blasBounds.Data());
        RefitLbvh(cpu, InstanceWorldBounds(instances, kBlasBounds));
        ExpectSameNodes(cpu.nodes, gpu.Download().nodes);
        // And a second refit from there, with no walk's marks left behind by the first.
        for (uint32_t i = 0; i < n; ++i) {
            SetTransform(instances[i], RandomPlacement(rng, 40.0f));
            SetPlacement(onDevice[i], instances[i]);
        }
        records.Upload(onDevice);
        gpu.Refit(records.Data(), blasBounds.Data());
        RefitLbvh(cpu, InstanceWorldBounds(instances, kBlasBounds));
        ExpectSameNodes(cpu.nodes, gpu.Download().nodes);
    }
}

}  // namespace
}  // namespace rtrt
