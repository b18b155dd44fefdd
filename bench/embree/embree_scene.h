#pragma once
// An Embree 3 scene holding what a RenderScene holds, for `rtrt bench embree`: each BLAS's
// primitives in its leaf order (Embree's primID is rtrt's leaf slot, so rtrt's shading reads the
// hit as its own), each instance as an Embree instance whose ID is rtrt's instance index. A scene
// of one instance puts that instance's geometry in the top scene directly, as an Embree user
// would, with the geometry ID standing for the instance.
#include <embree3/rtcore.h>

#include "engine/render_rt/render_scene.h"

namespace rtrt {

class EmbreeScene {
  public:
    // Builds with Embree's high-quality (spatial-split) builder, its fastest for tracing.
    // Throws std::runtime_error with Embree's message if Embree fails.
    explicit EmbreeScene(const RenderScene& scene);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    RTCScene Handle() const { return top_; }
    double BuildMs() const { return buildMs_; }

  private:
    RTCDevice device_ = nullptr;
    RTCScene top_ = nullptr;
    std::vector<RTCScene> blasScenes_;
    double buildMs_ = 0.0;
};

}  // namespace rtrt
