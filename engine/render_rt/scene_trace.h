#pragma once
// Closest-hit and any-hit queries of a specialised kernel against the whole scene.
#include <concepts>

#include "engine/render_rt/render_scene_view.h"
#include "engine/render_rt/trace_policy.h"

namespace rtrt {

// A policy may answer the scene queries itself, with static SceneIntersect(tlas, ray, hit) and
// SceneOccluded(tlas, ray): the Embree comparison (bench/embree) traces the same frame through
// another library's traversal that way. Production's policy does not.
template <class Policy>
concept AnswersSceneQueries = requires(const TlasView& tlas, const Ray& ray, SceneHit* hit) {
    { Policy::SceneIntersect(tlas, ray, hit) } -> std::same_as<bool>;
    { Policy::SceneOccluded(tlas, ray) } -> std::same_as<bool>;
};

// The scene traversal a specialisation uses: on the GPU, kernels with kFeatureManyInstances take
// the single loop over both levels; otherwise (and always on the CPU) the nested form. Both take
// the policy's primitive tests (trace_policy.h).
template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline bool TraceIntersect(const TlasView& tlas, const Ray& ray, SceneHit* hit,
                                 TraversalStats* stats) {
    if constexpr (AnswersSceneQueries<Policy>) return Policy::SceneIntersect(tlas, ray, hit);
#if defined(RT_ON_GPU)
    if constexpr ((kFeatures & kFeatureManyInstances) != 0) {
        float tMax = ray.tMax;
        return TraverseTwoLevel<Query::kIntersect, Policy>(tlas, ray, tMax, hit, stats);
    }
#endif
    return IntersectScene<Policy>(tlas, ray, hit, stats);
}

template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline bool TraceOccluded(const TlasView& tlas, const Ray& ray) {
    if constexpr (AnswersSceneQueries<Policy>) return Policy::SceneOccluded(tlas, ray);
#if defined(RT_ON_GPU)
    if constexpr ((kFeatures & kFeatureManyInstances) != 0) {
        float tMax = ray.tMax;
        return TraverseTwoLevel<Query::kOccluded, Policy>(tlas, ray, tMax, nullptr, nullptr);
    }
#endif
    return OccludedScene<Policy>(tlas, ray);
}

}  // namespace rtrt
