#pragma once
// Textures: RGBA8 texels (mip levels after each image) in one array per scene, a table of Texture
// records, and nearest, bilinear or trilinear sampling with glTF's wrap modes. Plain RT_HD code,
// no CUDA texture objects, so the CPU back end is the reference for the GPU's samples: bit for
// bit on one level, within the ulps of log2f where the level of detail blends two.
#include <cstdint>

#include "engine/geometry/primitives.h"
#include "engine/render_rt/shading/material.h"
#include "engine/render_rt/srgb.h"

namespace rtrt {

enum class TextureWrap : uint32_t { kRepeat = 0, kClampToEdge = 1, kMirroredRepeat = 2 };
enum class TextureFilter : uint32_t { kLinear = 0, kNearest = 1 };

// One image of the scene's texel array as a material uses it, 64 bytes. Texel (x, y) is
// texels[texelOffset + y * width + x], row 0 the top of the image; texture coordinate (0, 0) is
// its top-left corner (glTF). Records may share texels (one image under several transforms).
struct Texture {
    uint64_t texelOffset = 0;
    uint32_t width = 0, height = 0;
    TextureWrap wrapS = TextureWrap::kRepeat, wrapT = TextureWrap::kRepeat;
    TextureFilter filter = TextureFilter::kLinear;
    // 1: the texels are sRGB-encoded colours (glTF's base colour in a scene of linear colours),
    // decoded per texel before filtering; 0: used as they are.
    uint32_t srgb = 0;
    // Mip levels stored one after another from texelOffset (level l is max(1, width >> l) x
    // max(1, height >> l)); 1: the image alone.
    uint32_t levels = 1;
    // 1: uv is mapped by uvTransform (rows of a 2x3 affine map, KHR_texture_transform) first.
    uint32_t transformed = 0;
    float uvTransform[6] = {1, 0, 0, 0, 1, 0};
};
static_assert(sizeof(Texture) == 64);

// KHR_texture_transform's map: scale, then rotate by `rotation` radians (counter-clockwise in uv
// with v down, as the specification's matrix says), then offset.
inline void SetUvTransform(Texture* t, vec2 offset, float rotation, vec2 scale) {
    const float c = cosf(rotation), s = sinf(rotation);
    const float m[6] = {c * scale.x, s * scale.y, offset.x, -s * scale.x, c * scale.y, offset.y};
    for (int i = 0; i < 6; ++i) t->uvTransform[i] = m[i];
    t->transformed = 1;
}

RT_HD inline vec2 TransformUv(const Texture& t, vec2 uv) {
    if (!t.transformed) return uv;
    const float* m = t.uvTransform;
    return vec2(m[0] * uv.x + m[1] * uv.y + m[2], m[3] * uv.x + m[4] * uv.y + m[5]);
}

// Reduces a coordinate to one period of its wrap mode before it is scaled to texels, so that a
// huge coordinate never overflows the integer texel index.
RT_HD inline float ReduceCoordinate(float u, TextureWrap wrap) {
    if (!(u == u) || fabsf(u) > 1e30f) return 0.0f;  // NaN or beyond any period: the first texel
    if (wrap == TextureWrap::kClampToEdge) return fminf(fmaxf(u, 0.0f), 1.0f);
    const float period = wrap == TextureWrap::kMirroredRepeat ? 2.0f : 1.0f;
    return u - period * floorf(u / period);
}

// A texel index at most one period (n texels, 2n mirrored) off the range mapped into [0, n),
// without integer division: ReduceCoordinate leaves every index SampleLevel makes in that span.
RT_HD inline uint32_t WrapTexel(int i, int n, TextureWrap wrap) {
    if (wrap == TextureWrap::kClampToEdge) return uint32_t(i < 0 ? 0 : (i >= n ? n - 1 : i));
    if (wrap == TextureWrap::kRepeat) return uint32_t(i < 0 ? i + n : (i >= n ? i - n : i));
    const int m = i < 0 ? i + 2 * n : (i >= 2 * n ? i - 2 * n : i);
    return uint32_t(m < n ? m : 2 * n - 1 - m);
}

// One mip level's place in the texel array.
struct TextureLevel {
    uint64_t offset;
    int width, height;
};

RT_HD inline TextureLevel LevelOf(const Texture& t, uint32_t level) {
    TextureLevel l{t.texelOffset, int(t.width), int(t.height)};
    for (uint32_t i = 0; i < level; ++i) {
        l.offset += uint64_t(l.width) * uint64_t(l.height);
        l.width = l.width > 1 ? l.width / 2 : 1;
        l.height = l.height > 1 ? l.height / 2 : 1;
    }
    return l;
}

// The texels of a texture with its levels.
inline uint64_t TexelCount(uint32_t width, uint32_t height, uint32_t levels) {
    uint64_t count = 0;
    for (uint32_t i = 0; i < levels; ++i) {
        count += uint64_t(width) * height;
        width = width > 1 ? width / 2 : 1;
        height = height > 1 ? height / 2 : 1;
    }
    return count;
}

// Levels down to 1 x 1: floor(log2(max(width, height))) + 1.
inline uint32_t FullMipLevels(uint32_t width, uint32_t height) {
    uint32_t levels = 1;
    for (uint32_t size = width > height ? width : height; size > 1; size /= 2) ++levels;
    return levels;
}

RT_HD inline vec3 TexelColor(const Texture& t, const TextureLevel& l, const uint32_t* texels,
                             uint32_t x, uint32_t y) {
    const uint32_t rgba = texels[l.offset + uint64_t(y) * uint32_t(l.width) + x];
    const vec3 c =
        vec3(float(rgba & 0xffu), float((rgba >> 8) & 0xffu), float((rgba >> 16) & 0xffu)) *
        (1.0f / 255.0f);
    return t.srgb ? vec3(SrgbDecode(c.x), SrgbDecode(c.y), SrgbDecode(c.z)) : c;
}

// The colour of one level at (already transformed) texture coordinate uv: the texel under it
// (nearest), or the bilinear blend of the four texels around it, texel centres at
// ((i + 0.5) / width, (j + 0.5) / height).
RT_HD inline vec3 SampleLevel(const Texture& t, const uint32_t* texels, vec2 uv, uint32_t level,
                              bool nearest) {
    const TextureLevel l = LevelOf(t, level);
    const int w = l.width, h = l.height;
    const float x = ReduceCoordinate(uv.x, t.wrapS) * float(w);
    const float y = ReduceCoordinate(uv.y, t.wrapT) * float(h);
    if (nearest)
        return TexelColor(t, l, texels, WrapTexel(int(floorf(x)), w, t.wrapS),
                          WrapTexel(int(floorf(y)), h, t.wrapT));
    const float fx = x - 0.5f, fy = y - 0.5f;
    const float x0f = floorf(fx), y0f = floorf(fy);
    const float ax = fx - x0f, ay = fy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const uint32_t xa = WrapTexel(x0, w, t.wrapS), xb = WrapTexel(x0 + 1, w, t.wrapS);
    const uint32_t ya = WrapTexel(y0, h, t.wrapT), yb = WrapTexel(y0 + 1, h, t.wrapT);
    const vec3 top =
        (1.0f - ax) * TexelColor(t, l, texels, xa, ya) + ax * TexelColor(t, l, texels, xb, ya);
    const vec3 bottom =
        (1.0f - ax) * TexelColor(t, l, texels, xa, yb) + ax * TexelColor(t, l, texels, xb, yb);
    return (1.0f - ay) * top + ay * bottom;
}

// The colour at texture coordinate uv on the full-resolution image (its filter as it says).
RT_HD inline vec3 SampleTexture(const Texture& t, const uint32_t* texels, vec2 uv) {
    return SampleLevel(t, texels, TransformUv(t, uv), 0, t.filter == TextureFilter::kNearest);
}

// log2 of how many texels of level 0 a footprint covers, less log2 of its size in texture
// coordinates: 0.5 log2(width height |det uvTransform|).
RT_HD inline float TextureLodBias(const Texture& t) {
    float area = float(t.width) * float(t.height);
    if (t.transformed)
        area *= fabsf(t.uvTransform[0] * t.uvTransform[4] - t.uvTransform[1] * t.uvTransform[3]);
    return 0.5f * log2f(fmaxf(area, 1e-30f));
}

// Trilinear filtering for a footprint lodNoBias (log2 of its size in texture coordinates, see
// TextureFootprint): the blend of the two levels around lod; level 0 magnified by the texture's
// own filter. Textures without levels sample their image.
RT_HD inline vec3 SampleTexture(const Texture& t, const uint32_t* texels, vec2 uv,
                                float lodNoBias) {
    uv = TransformUv(t, uv);
    const bool nearest = t.filter == TextureFilter::kNearest;
    const float lod = lodNoBias + TextureLodBias(t);
    if (t.levels <= 1 || !(lod > 0.0f)) return SampleLevel(t, texels, uv, 0, nearest);
    const float top = float(t.levels - 1);
    if (lod >= top) return SampleLevel(t, texels, uv, t.levels - 1, false);
    const float base = floorf(lod);
    const float blend = lod - base;
    const uint32_t level = uint32_t(base);
    return (1.0f - blend) * SampleLevel(t, texels, uv, level, level == 0 && nearest) +
           blend * SampleLevel(t, texels, uv, level + 1, false);
}

// The texture coordinate of a hit on a triangle with per-vertex uvs.
RT_HD inline vec2 InterpolateUv(const TriangleUvs& t, float b1, float b2) {
    return (1.0f - b1 - b2) * t.uv0 + b1 * t.uv1 + b2 * t.uv2;
}

// log2 of a ray cone's footprint in texture coordinates on a triangle (Akenine-Moller et al.,
// "Texture Level of Detail Strategies for Real-Time Ray Tracing", Ray Tracing Gems ch. 20):
// 0.5 log2(uv area / world area) + log2(coneWidth / |cos|), with the world edges e1, e2 after the
// instance's transform and cosine the angle between the ray and the surface's normal.
RT_HD inline float TextureFootprint(const TriangleUvs& t, vec3 e1, vec3 e2, float coneWidth,
                                    float cosine) {
    const vec2 d1 = t.uv1 - t.uv0, d2 = t.uv2 - t.uv0;
    const float uvArea = fabsf(d1.x * d2.y - d2.x * d1.y);
    const float worldArea = glm::length(glm::cross(e1, e2));
    if (!(uvArea > 0.0f) || !(worldArea > 0.0f)) return -1e30f;
    return 0.5f * log2f(uvArea / worldArea) +
           log2f(fmaxf(coneWidth, 1e-30f) / fmaxf(fabsf(cosine), 1e-3f));
}

}  // namespace rtrt
