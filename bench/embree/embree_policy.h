#pragma once
// The trace policy of `rtrt bench embree`: production's (trace_policy.h) with the scene queries
// answered by Embree (AnswersSceneQueries in scene_trace.h), so that a frame through it runs
// rtrt's camera, shading and secondary rays unchanged around Embree's single-ray traversal.
#include <embree3/rtcore.h>

#include "engine/render_rt/scene_trace.h"

namespace rtrt {

struct EmbreePolicy : TracePolicy {
    // The scene every query goes to; set before a frame, read-only while it traces.
    static inline RTCScene scene = nullptr;

    static bool SceneIntersect(const TlasView&, const Ray& ray, SceneHit* hit) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh;
        SetRay(ray, &rh.ray);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
        hit->t = rh.ray.tfar;
        hit->instance =
            rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0] : rh.hit.geomID;
        hit->prim = rh.hit.primID;
        // Embree's (u, v) weigh the second and third vertex, as rtrt's (b1, b2) do.
        hit->b1 = rh.hit.u;
        hit->b2 = rh.hit.v;
        return true;
    }

    static bool SceneOccluded(const TlasView&, const Ray& ray) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay r;
        SetRay(ray, &r);
        rtcOccluded1(scene, &context, &r);
        return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
    }

  private:
    static void SetRay(const Ray& ray, RTCRay* r) {
        r->org_x = ray.origin.x;
        r->org_y = ray.origin.y;
        r->org_z = ray.origin.z;
        r->dir_x = ray.dir.x;
        r->dir_y = ray.dir.y;
        r->dir_z = ray.dir.z;
        r->tnear = 0.0f;
        r->tfar = ray.tMax;
        r->time = 0.0f;
        r->mask = 0xffffffffu;
        r->id = 0;
        r->flags = 0;
    }
};

}  // namespace rtrt
