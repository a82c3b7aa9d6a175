#pragma once
// Adam for a flat parameter buffer (the environment map's texels, the roughness net's weights): one group,
// stepped with the same element update as the Gaussians' groups (train/optimizer/adam_kernel.h).
#include "core/compute/buffer.h"

namespace goris {

class FlatAdam {
 public:
  float beta1 = 0.9f, beta2 = 0.999f, eps = 1e-15f;  // eps as the Gaussians' groups (3DGS)

  FlatAdam() = default;
  FlatAdam(std::size_t n, Device device) : m_(n, device), v_(n, device) { reset(); }

  // One bias-corrected update of params from grads (the gradients are left as they are). `what` names the
  // parameters in errors (size or device mismatch).
  void step(Buffer<float>& params, const Buffer<float>& grads, float lr, const char* what);
  void reset();

  int steps() const { return steps_; }
  void set_steps(int s) { steps_ = s; }
  Buffer<float>& first_moment() { return m_; }
  Buffer<float>& second_moment() { return v_; }
  const Buffer<float>& first_moment() const { return m_; }
  const Buffer<float>& second_moment() const { return v_; }

 private:
  Buffer<float> m_, v_;
  int steps_ = 0;
};

}  // namespace goris
