#include "game/scene/scene_deform.h"

#include <cmath>

namespace rtrt {
namespace {

uint32_t ParseAxis(JsonFields& f, const std::string& key, const std::string& fallback) {
    const std::string axis = f.String(key, fallback);
    if (axis == "x") return 0;
    if (axis == "y") return 1;
    if (axis == "z") return 2;
    f.Fail(key, "expected \"x\", \"y\" or \"z\", got \"" + axis + "\"");
}

}  // namespace

// wave:  {"amplitude": A, "wavelength": L, "speed": S, "axis": "y", "along": "x", "phase": T,
//         "centre": [x, y, z]}: p[axis] += A sin(2 pi ((p[along] - centre) - S t) / L)
// twist: {"angle": radians per unit along the axis at full swing, "speed": rad/s of the swing,
//         "axis": "y", "phase": T, "centre": [x, y, z]}
ProceduralDeform ParseDeform(const Json& j, const std::string& path, const Aabb& model,
                             const std::string& file) {
    JsonFields top(j, path, file);
    ProceduralDeform d;
    const bool wave = top.Has("wave"), twist = top.Has("twist");
    if (wave == twist) top.Fail("", "expected exactly one of \"wave\" or \"twist\"");
    const std::string kind = wave ? "wave" : "twist";
    JsonFields f(top.Get(kind), top.Path(kind), file);
    // Bounded as the scene's own places and times are: a wavelength of 1e-45, a phase of 3e38 or
    // a centre of 3e38 made every vertex NaN and the model vanish.
    d.centre = f.Position("centre", model.IsEmpty() ? vec3(0.0f) : model.Centroid());
    d.time = f.InRange("phase", -1e6f, 1e6f, 0.0f);
    if (wave) {
        d.kind = ProceduralDeformKind::kWave;
        d.amplitude = f.Number("amplitude");
        if (!(std::fabs(d.amplitude) <= kMaxSceneCoordinate))
            f.Fail("amplitude", "must be at most 1e7 in magnitude");
        d.wavelength = f.Positive("wavelength");
        if (!(d.wavelength >= 1e-6f && d.wavelength <= kMaxSceneCoordinate))
            f.Fail("wavelength", "must be between 1e-6 and 1e7");
        d.speed = f.InRange("speed", -1e6f, 1e6f, 1.0f);
        d.axis = ParseAxis(f, "axis", "y");
        d.along = ParseAxis(f, "along", "x");
        if (d.axis == d.along) f.Fail("along", "must differ from \"axis\"");
    } else {
        d.kind = ProceduralDeformKind::kTwist;
        d.amplitude = f.Number("angle");
        if (!(std::fabs(d.amplitude) <= 1e6f)) f.Fail("angle", "must be at most 1e6 in magnitude");
        d.speed = f.InRange("speed", -1e6f, 1e6f, 1.0f);
        d.axis = ParseAxis(f, "axis", "y");
    }
    f.Finish();
    top.Finish();
    return d;
}

}  // namespace rtrt
