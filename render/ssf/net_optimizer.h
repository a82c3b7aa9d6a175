#pragma once
// The roughness net as one optimiser group: Adam moments for its flat parameter buffer, stepped with the
// training engine's Adam element update (core/train/adam_kernel.h, the same maths as the Gaussians' groups).
// The trainer owns the learning-rate schedule (DESIGN.md §4: 1e-5, eased in between 4K and 10K iterations)
// and calls step() after backward() has filled net.grads().
#include "core/compute/buffer.h"
#include "render/ssf/roughness_net.h"

namespace goris::ssf {

class NetAdam {
 public:
  float beta1 = 0.9f, beta2 = 0.999f, eps = 1e-15f;  // eps as the Gaussians' groups (3DGS)

  explicit NetAdam(const RoughnessNet<float>& net);

  // One bias-corrected Adam update of every parameter from net.grads() (the gradients are left as they are).
  void step(RoughnessNet<float>& net, float lr);
  // Forgets the moments and the step count.
  void reset();

  int steps() const { return steps_; }
  Buffer<float>& first_moment() { return m_; }  // exposed for checkpoints
  Buffer<float>& second_moment() { return v_; }
  void set_steps(int s) { steps_ = s; }

 private:
  Buffer<float> m_, v_;
  int steps_ = 0;
};

}  // namespace goris::ssf
