#pragma once
// Stage-1 losses of the intrinsic decomposition (paper Sec. 3.2, supplementary S1.5; docs/design/maths.md,
// Stage 1), on planar images [C][H][W]. Each returns the loss and ADDS weight * dL/d(input) into the gradient
// buffers (null = not wanted). Masks and targets are constants. Every loss is a mean over the H*W pixels, so
// its scale does not depend on the resolution. T = float in training, double in the gradient tests.
namespace goris {

// Normal prior L_n = (1/HW) sum_p m_p sum_c |N_pc - Ngt_pc|, N = n / |n| the normalised rendered normal
// (camera space), Ngt a unit normal in camera space. Pixels with |n| ~ 0 or m_p = 0 add nothing.
template <class T>
T normal_prior_loss(const T* normal, const T* prior, const T* mask, int width, int height, T* grad_normal,
                    T weight = T(1));

// Edge-aware (bilateral) smoothness L_s = (1/HW) sum_p m_p sum_{d in x,y} |X(p+d) - X(p)|_1 e^{-g_d(p)},
// g_d(p) = mean_c |I(p+d) - I(p)| of the ground-truth image I ([3][H][W]): material edges are allowed where
// the photo has edges. With normalize_x, X is taken per pixel as x / |x| (for normal maps; |x| ~ 0 pixels
// then contribute nothing).
template <class T>
T edge_aware_smoothness(const T* x, int channels, const T* image, const T* mask, int width, int height, T* grad_x,
                        T weight = T(1), bool normalize_x = false);

// Region loss L_M = (1/HW) sum_p Mgt_p M_p: pushes the region weight M to 0 (glossy) on the glossy mask.
template <class T>
T region_loss(const T* region, const T* glossy_mask, int width, int height, T* grad_region, T weight = T(1));

// Label BCE (1/HW) sum_p -[y log l + (1 - y) log(1 - l)], l the rendered label clamped to [eps, 1 - eps]
// (outside that range the gradient is zero), y the object mask in [0, 1].
template <class T>
T label_bce_loss(const T* label, const T* object_mask, int width, int height, T* grad_label, T weight = T(1),
                 T eps = T(1e-4));

}  // namespace goris
