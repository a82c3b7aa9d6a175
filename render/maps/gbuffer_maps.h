#pragma once
// Viewable 8-bit-ready RGB images of G-buffer channels (planar float inputs, as the rasterizer writes them):
// colour as is, scalar maps in grey, depth through the TURBO colour map on normalised inverse depth,
// normals as n * 0.5 + 0.5. Pixels with (almost) no coverage are black in depth and normal maps.
#include "core/io/image.h"

namespace goris {

// Expected depth (depth / alpha) where alpha > min_alpha, mapped to TURBO on 1/depth normalised between its
// 1st and 99th percentile over those pixels (near = red, far = blue). `depth_is_weighted`: the input is the
// alpha-weighted sum (the rasterizer's `depth`), else a plain depth (the median depth).
Image depth_to_turbo(const float* depth, const float* alpha, int width, int height, bool depth_is_weighted,
                     float min_alpha = 0.05f);

// Camera-space normals ([3][H][W], any length) as normalize(n) * 0.5 + 0.5 where alpha > min_alpha.
Image normals_to_rgb(const float* normal, const float* alpha, int width, int height, float min_alpha = 0.05f);

}  // namespace goris
