#pragma once
// Depth-normal consistency (RaDe-GS / 2DGS): the rendered normal should agree with the normal of the
// surface the depth map describes.
//
// For every interior pixel (x, y) (one pixel from the border), camera-space points P = depth * r with
// r = ((x + 0.5 - cx) / fx, (y + 0.5 - cy) / fy, 1), central differences dx = P(x+1, y) - P(x-1, y),
// dy = P(x, y+1) - P(x, y-1), and the depth normal n_d = normalize(dy x dx), which faces the camera
// (OpenCV axes: a fronto-parallel plane gives (0, 0, -1)), like the rasterizer's normals.
// Loss = sum_p w_p (1 - cos(n_p, n_d,p)) / (number of interior pixels), with n_p the rendered normal
// (any length; it is normalised). Pixels where w_p == 0, or where either normal is degenerate (zero
// length), add nothing. Gradients go to both the depth and the rendered normal (accumulated, scaled by
// `weight`); the pixel weights are constants.
namespace goris {

template <class T>
T depth_normal_loss(const T* depth,        // [H][W] camera z
                    const T* normal,       // [3][H][W] camera space
                    const T* pixel_weight, // [H][W] or null (all 1)
                    int width, int height, T fx, T fy, T cx, T cy,
                    T* grad_depth = nullptr,   // [H][W] or null
                    T* grad_normal = nullptr,  // [3][H][W] or null
                    T weight = T(1));

// RaDe-GS's form on rasterizer outputs: (1 - r) * L(expected depth) + r * L(median depth) with the same
// rendered normal, where expected depth = depth_weighted / max(alpha, min_alpha) and the pixel weights
// are the rendered alpha (constants: background pixels carry no surface). Gradients (accumulated,
// scaled by `weight`) go to the weighted depth, the alpha (through the division), the median depth and
// the normal; any gradient pointer may be null.
template <class T>
T rendered_depth_normal_loss(const T* depth_weighted, const T* alpha, const T* median_depth, const T* normal,
                             int width, int height, T fx, T fy, T cx, T cy, T median_ratio, T* grad_depth,
                             T* grad_alpha, T* grad_median, T* grad_normal, T weight = T(1),
                             T min_alpha = T(1e-4));

// The depth normal alone ([3][H][W]; zero at the border and where degenerate), for display.
template <class T>
void normal_from_depth(const T* depth, int width, int height, T fx, T fy, T cx, T cy, T* normal_out);

}  // namespace goris
