#pragma once
// LDR-FLIP, the perceptual difference of "FLIP: A Difference Evaluator for Alternating Images" (Andersson,
// Nilsson, Akenine-Moller, Oskarsson, Astrom, Fairchild, HPG 2020), written from the paper's description.
// Images are sRGB-encoded in [0, 1], planar [3][H][W] (channel-major, row-major per channel), as the
// rasterizer lays them out. The error map is [H][W] in [0, 1]: 0 = no perceived difference.
//
// Colour pipeline: sRGB -> linear RGB -> XYZ -> YCxCz (D65 white), the paper's contrast sensitivity filters
// per opponent channel, back to linear RGB clamped to [0, 1], CIELab, Hunt adjustment, HyAB distance, ^0.7,
// then the cmax / pc / pt remapping to [0, 1]. Feature pipeline: first and second derivatives of a Gaussian
// (edges, points) on the normalised achromatic channel, the larger difference of the two, / sqrt(2), ^0.5.
// Per pixel E = Ec^(1 - Ef). Filters clamp to the edge at the image border.
//
// The metric is symmetric: swapping test and reference gives the same map bit for bit (both images pass
// through the same filters; HyAB and the feature difference use absolute differences).
#include <cstddef>
#include <vector>

namespace goris {

// The paper's standard viewing condition: a 0.7 m wide 3840-pixel monitor seen from 0.7 m.
inline constexpr double kFlipDefaultPpd = 67.0;

// Pixels per degree of visual angle for a monitor `monitor_width_m` wide, `resolution_x` pixels across,
// seen from `distance_m`.
double flip_pixels_per_degree(double distance_m = 0.7, double monitor_width_m = 0.7, double resolution_x = 3840);

// The per-pixel FLIP error map (width * height values in [0, 1]); `mean` (optional) receives its mean.
// Throws std::invalid_argument on null images, a non-positive size or ppd.
std::vector<float> flip_error_map(const float* test, const float* reference, int width, int height,
                                  double ppd = kFlipDefaultPpd, double* mean = nullptr);

// Mean of an error map: plain when weight is null, else sum(w e) / sum(w) over the pixels with w > 0
// (weight is [H][W]); NaN when no pixel has a positive weight.
double flip_pooled_mean(const std::vector<float>& error_map, const float* weight = nullptr);

// flip_error_map followed by flip_pooled_mean.
double flip_mean(const float* test, const float* reference, int width, int height, double ppd = kFlipDefaultPpd,
                 const float* weight = nullptr);

}  // namespace goris
