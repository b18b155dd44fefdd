#pragma once
// Mip levels for textures: each level the 2x2 box filter of the one above (the last row or column
// of an odd size folded into its neighbour's average), sRGB-encoded colours averaged in linear
// light and encoded again.
#include <cstdint>
#include <vector>

namespace rtrt {

// Level 0 (rgba, width x height RGBA8, row 0 the top) followed by `levels` - 1 smaller levels,
// as Texture::levels lays them out.
std::vector<uint32_t> BuildMipChain(const uint32_t* rgba, uint32_t width, uint32_t height,
                                    uint32_t levels, bool srgb);

}  // namespace rtrt
