// The GPU LBVH equals the CPU LBVH for the same input: the same nodes (bit for bit: bounds come
// from min/max only), leaf order and parents; for 0, 1, 2, 1000 and 1,000,000 instances, all at
// one point, one far outlier, and NaN and signed zeros among the centroids. Refit on the GPU equals
// refit on the CPU. Label gpu.
#include "engine/bvh/build/gpu_lbvh.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "engine/render_rt/renderer.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

void ExpectSameTree(const Lbvh& cpu, const Lbvh& gpu) {
    ASSERT_EQ(cpu.nodes.size(), gpu.nodes.size());
    ASSERT_EQ(cpu.primOrder, gpu.primOrder);
    ASSERT_EQ(cpu.parents, gpu.parents);
    for (size_t i = 0; i < cpu.nodes.size(); ++i) {
        ASSERT_EQ(std::memcmp(&cpu.nodes[i], &gpu.nodes[i], sizeof(BvhNode)), 0) << "node " << i;
    }
}

void ExpectGpuEqualsCpu(const std::vector<Aabb>& boxes) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    DeviceBuffer<Aabb> device{std::span<const Aabb>(boxes)};
    GpuLbvh gpu;
    gpu.Build(device.Data(), uint32_t(boxes.size()));
    ExpectSameTree(BuildLbvh(boxes), gpu.Download());
}

TEST(GpuLbvh, EqualsCpuForManySizes) {
    for (uint32_t n : {0u, 1u, 2u, 3u, 1000u, 1000000u}) {
        SCOPED_TRACE(n);
        ExpectGpuEqualsCpu(test::RandomBoxes(n, 100.0f, n + 1));
    }
}

TEST(GpuLbvh, CentroidBoundsSkipNanAsTheCpuDoes) {
    // A NaN box and signed zeros among ordinary boxes: the centroid bounds, hence the Morton codes
    // and the trees, agree.
    std::vector<Aabb> boxes = test::RandomBoxes(3000, 10.0f, 11);
    boxes[17] = {vec3(std::nanf(""), 1, 2), vec3(std::nanf(""), 1, 2)};
    boxes.push_back({vec3(-1e30f), vec3(-1e30f)});
    ExpectGpuEqualsCpu(boxes);
    // Zeros of both signs as the lowest centroids of every axis (boxes shifted to positive
    // coordinates), +0 first so that the CPU's bound is +0 and the GPU's -0.
    for (Aabb& b : boxes) {
        b.min = glm::abs(b.min) + vec3(1.0f);
        b.max = b.min + vec3(0.5f);
    }
    boxes[5] = {vec3(0.0f), vec3(0.0f)};
    boxes[6] = {vec3(-0.0f), vec3(-0.0f)};
    ExpectGpuEqualsCpu(boxes);
}

TEST(GpuLbvh, EqualsCpuWithAllAtOnePoint) {
    ExpectGpuEqualsCpu(std::vector<Aabb>(10000, Aabb{vec3(1, 2, 3), vec3(1, 2, 3)}));
}

TEST(GpuLbvh, EqualsCpuWithOneFarOutlier) {
    std::vector<Aabb> boxes = test::RandomBoxes(5000, 1.0f, 7);
    boxes.push_back({vec3(1e7f), vec3(1e7f + 1.0f)});
    ExpectGpuEqualsCpu(boxes);
}

TEST(GpuLbvh, RefitEqualsCpuRefit) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    std::vector<Aabb> boxes = test::RandomBoxes(20000, 30.0f, 3);
    DeviceBuffer<Aabb> device{std::span<const Aabb>(boxes)};
    GpuLbvh gpu;
    gpu.Build(device.Data(), uint32_t(boxes.size()));
    Lbvh cpu = BuildLbvh(boxes);
    for (Aabb& b : boxes) b.max += vec3(0.25f, 0.0f, 0.5f);
    device.Upload(boxes);
    gpu.Refit(device.Data());
    RefitLbvh(cpu, boxes);
    ExpectSameTree(cpu, gpu.Download());
}

}  // namespace
}  // namespace rtrt
