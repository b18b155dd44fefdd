#include "bench/embree/embree_scene.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "engine/core/timer.h"

namespace rtrt {
namespace {

void ThrowOnError(RTCDevice device, const char* what) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                                 std::to_string(int(error)) + ")");
}

// The BLAS's primitives in leaf order as one geometry, moved by transform (the identity for an
// instanced BLAS, whose instance carries the transform).
RTCGeometry MakeGeometry(RTCDevice device, const Blas& blas, const Affine& transform) {
    const uint32_t count = blas.PrimCount();
    RTCGeometry geometry;
    if (blas.kind == GeometryKind::kTriangles) {
        geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
        auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), count));
        ThrowOnError(device, "allocating a triangle geometry");
        for (uint32_t s = 0; s < count; ++s) {
            const Triangle& t = blas.triangles[s];
            const vec3 v[3] = {transform.Point(t.v0), transform.Point(t.v1), transform.Point(t.v2)};
            std::memcpy(vertices + 9 * size_t(s), v, sizeof(v));
            for (uint32_t k = 0; k < 3; ++k) indices[3 * size_t(s) + k] = 3 * s + k;
        }
    } else {
        // The one-instance path bakes only the identity into spheres (anything else goes
        // through an Embree instance, which keeps rtrt's transformed-sphere semantics).
        geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        auto* points = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), count));
        ThrowOnError(device, "allocating a sphere geometry");
        for (uint32_t s = 0; s < count; ++s) {
            const vec3 c = transform.Point(blas.spheres[s].center);
            const float p[4] = {c.x, c.y, c.z, blas.spheres[s].radius};
            std::memcpy(points + 4 * size_t(s), p, sizeof(p));
        }
    }
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(geometry);
    ThrowOnError(device, "committing a geometry");
    return geometry;
}

bool IsIdentity(const Affine& a) {
    const Affine id = Affine::Identity();
    return std::memcmp(&a, &id, sizeof(Affine)) == 0;
}

}  // namespace

EmbreeScene::EmbreeScene(const RenderScene& scene) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
    Stopwatch timer;
    top_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_HIGH);
    const bool direct = scene.instances.size() == 1 &&
                        (IsIdentity(scene.instances[0].ObjectToWorld()) ||
                         scene.blases[scene.instances[0].blasId]->kind == GeometryKind::kTriangles);
    if (direct) {
        const Instance& inst = scene.instances[0];
        RTCGeometry g = MakeGeometry(device_, *scene.blases[inst.blasId], inst.ObjectToWorld());
        rtcAttachGeometryByID(top_, g, 0);
        rtcReleaseGeometry(g);
    } else {
        for (const auto& blas : scene.blases) {
            RTCScene s = rtcNewScene(device_);
            rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
            RTCGeometry g = MakeGeometry(device_, *blas, Affine::Identity());
            rtcAttachGeometryByID(s, g, 0);
            rtcReleaseGeometry(g);
            rtcCommitScene(s);
            ThrowOnError(device_, "building a BLAS scene");
            blasScenes_.push_back(s);
        }
        for (uint32_t i = 0; i < scene.instances.size(); ++i) {
            const Instance& inst = scene.instances[i];
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(g, blasScenes_[inst.blasId]);
            rtcSetGeometryTimeStepCount(g, 1);
            // Affine's three rows are Embree's row-major 3x4.
            const Affine objectToWorld = inst.ObjectToWorld();
            rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, &objectToWorld);
            rtcCommitGeometry(g);
            rtcAttachGeometryByID(top_, g, i);
            rtcReleaseGeometry(g);
        }
    }
    rtcCommitScene(top_);
    ThrowOnError(device_, "building the scene");
    buildMs_ = timer.Milliseconds();
}

EmbreeScene::~EmbreeScene() {
    if (top_) rtcReleaseScene(top_);
    for (RTCScene s : blasScenes_) rtcReleaseScene(s);
    if (device_) rtcReleaseDevice(device_);
}

}  // namespace rtrt
