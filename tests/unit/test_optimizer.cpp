// Adam against hand-computed steps, learning-rate schedules, and the densification bookkeeping: clone /
// split / prune keep every parameter row and its Adam moments aligned, and the counts are right.
#include <cmath>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "core/compute/finite_check.h"
#include "core/scene/gaussian_kernels.h"
#include "core/util/error.h"
#include "tests/support/test_support.h"
#include "train/optimizer/adam.h"
#include "train/optimizer/densify.h"
#include "train/optimizer/lr_schedule.h"

using namespace goris;

TEST(Adam, MatchesHandComputedSteps) {
  GaussianModel m(Device::CPU);
  m.allocate(2);
  float* op = m.values(Param::OpacityLogit);
  op[0] = 1.0f;
  op[1] = -2.0f;
  GaussianAdam adam;
  // Reference in double: torch.optim.Adam's update.
  double p = 1.0, mm = 0, vv = 0;
  const double grads[3] = {0.5, -1.0, 0.25};
  for (int t = 1; t <= 3; ++t) {
    m.grads(Param::OpacityLogit)[0] = float(grads[t - 1]);
    m.grads(Param::OpacityLogit)[1] = 0.0f;
    adam.step(m, ParamGroup::Opacity, 0.1f);
    mm = 0.9 * mm + 0.1 * grads[t - 1];
    vv = 0.999 * vv + 0.001 * grads[t - 1] * grads[t - 1];
    const double mhat = mm / (1 - std::pow(0.9, t)), vhat = vv / (1 - std::pow(0.999, t));
    p -= 0.1 * mhat / (std::sqrt(vhat) + 1e-15);
    EXPECT_NEAR(op[0], p, 1e-6) << "step " << t;
    if (t == 1) EXPECT_NEAR(op[0], 0.9, 1e-6);  // the first two steps worked out by hand
    if (t == 2) EXPECT_NEAR(op[0], 0.9366104, 1e-6);
  }
  EXPECT_EQ(op[1], -2.0f) << "zero gradient and zero moments: no move";
  EXPECT_EQ(adam.steps[int(ParamGroup::Opacity)], 3);
  EXPECT_EQ(adam.steps[int(ParamGroup::Position)], 0);
}

TEST(Adam, GroupsTouchOnlyTheirColumns) {
  GaussianModel m(Device::CPU);
  m.allocate(3);
  ParamTensor& sh = m.tensor(Param::Sh);
  for (size_t i = 0; i < sh.value.size(); ++i) {
    sh.value[i] = 0.0f;
    sh.grad[i] = 1.0f;
  }
  GaussianAdam adam;
  adam.step(m, ParamGroup::ShRest, 0.01f);
  for (size_t r = 0; r < 3; ++r)
    for (int c = 0; c < 48; ++c) EXPECT_FLOAT_EQ(sh.value[r * 48 + c], c < 3 ? 0.0f : -0.01f) << r << "," << c;
  adam.step(m, ParamGroup::ShDc, 0.5f);
  EXPECT_FLOAT_EQ(sh.value[48], -0.5f);
  adam.step(m, ParamGroup::ShRest, 0.01f, 12);  // degree 1: coefficients 1..3 only
  EXPECT_FLOAT_EQ(sh.value[48 + 11], -0.02f);
  EXPECT_FLOAT_EQ(sh.value[48 + 12], -0.01f);
  EXPECT_EQ(adam.steps[int(ParamGroup::ShRest)], 2);
  reset_moments(m, ParamGroup::ShDc);
  EXPECT_EQ(sh.adam_m[48], 0.0f);
  EXPECT_NE(sh.adam_m[51], 0.0f);
}

TEST(LearningRate, ExponentialSchedule) {
  EXPECT_FLOAT_EQ(exponential_lr(0, 1.6e-4f, 1.6e-6f, 30000), 1.6e-4f);
  EXPECT_NEAR(exponential_lr(15000, 1.6e-4f, 1.6e-6f, 30000), 1.6e-5f, 1e-10f);
  EXPECT_FLOAT_EQ(exponential_lr(30000, 1.6e-4f, 1.6e-6f, 30000), 1.6e-6f);
  EXPECT_FLOAT_EQ(exponential_lr(90000, 1.6e-4f, 1.6e-6f, 30000), 1.6e-6f);
}

TEST(FiniteCheck, FindsTheFirstBadValue) {
  std::vector<float> v(100000, 1.0f);
  EXPECT_EQ(first_non_finite(v.data(), v.size(), Device::CPU), v.size());
  v[70000] = INFINITY;
  v[80000] = NAN;
  EXPECT_EQ(first_non_finite(v.data(), v.size(), Device::CPU), 70000u);
}

namespace {

// A model whose every value encodes (row, column) and whose moments encode the value, so any
// misalignment after surgery is visible: m = value + 1000, v = value + 2000.
GaussianModel tagged_model(size_t n) {
  GaussianModel m(Device::CPU);
  m.allocate(n);
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = m.tensor(Param(p));
    for (size_t r = 0; r < n; ++r)
      for (int c = 0; c < t.width; ++c) {
        const size_t k = r * t.width + c;
        t.value[k] = float(r) + 0.01f * float(c) + 0.001f * float(p);
        t.adam_m[k] = t.value[k] + 1000.0f;
        t.adam_v[k] = t.value[k] + 2000.0f;
      }
  }
  return m;
}

void set_gaussian(GaussianModel& m, size_t i, float log_scale, float opacity) {
  for (int a = 0; a < 3; ++a) m.values(Param::LogScale)[i * 3 + a] = log_scale;
  m.values(Param::OpacityLogit)[i] = kernels::logit(opacity);
  float* q = m.values(Param::Rotation) + i * 4;
  q[0] = 1;
  q[1] = q[2] = q[3] = 0;
  for (int p = 0; p < kParamCount; ++p) {  // keep the moment tags consistent with the new values
    ParamTensor& t = m.tensor(Param(p));
    for (int c = 0; c < t.width; ++c) {
      t.adam_m[i * t.width + c] = t.value[i * t.width + c] + 1000.0f;
      t.adam_v[i * t.width + c] = t.value[i * t.width + c] + 2000.0f;
    }
  }
}

}  // namespace

TEST(Densify, CloneSplitPruneKeepRowsAligned) {
  // extent 10: clone when max scale <= 0.1, world-size prune above 1.0 (with prune_large).
  const float extent = 10.0f;
  GaussianModel m = tagged_model(7);
  set_gaussian(m, 0, std::log(0.05f), 0.5f);  // high gradient, small -> clone
  set_gaussian(m, 1, std::log(0.5f), 0.5f);   // high gradient, large -> split in 2
  set_gaussian(m, 2, std::log(0.05f), 0.5f);  // low gradient -> kept as is
  set_gaussian(m, 3, std::log(0.05f), 0.01f); // transparent -> pruned
  set_gaussian(m, 4, std::log(0.05f), 0.01f); // transparent with high gradient -> pruned, no clone
  set_gaussian(m, 5, std::log(0.5f), 0.5f);   // seen by no view -> kept
  set_gaussian(m, 6, std::log(0.05f), 0.9f);  // gradient exactly at the threshold -> clone
  DensifyStats stats;
  stats.reset(7, Device::CPU);
  const float g[7] = {3e-4f, 5e-4f, 1e-4f, 1e-4f, 9e-4f, 0.0f, 2e-4f};
  for (int i = 0; i < 7; ++i) {
    stats.grad_accum[i] = g[i] * 4;
    stats.denom[i] = i == 5 ? 0.0f : 4.0f;
  }
  DensifySettings s;
  const DensifyCounts c = densify_and_prune(m, stats, s, extent, false, 42);
  EXPECT_EQ(c.before, 7u);
  EXPECT_EQ(c.cloned, 2u);
  EXPECT_EQ(c.split, 1u);
  EXPECT_EQ(c.pruned, 2u);
  // kept originals 0, 2, 5, 6; then clone of 0, children of 1 (x2), clone of 6.
  ASSERT_EQ(c.after, 8u);
  ASSERT_EQ(m.count(), 8u);
  const int src[8] = {0, 2, 5, 6, 0, 1, 1, 6};
  const bool fresh[8] = {false, false, false, false, true, true, true, true};
  for (int p = 0; p < kParamCount; ++p) {
    const ParamTensor& t = m.tensor(Param(p));
    for (int r = 0; r < 8; ++r)
      for (int c2 = 0; c2 < t.width; ++c2) {
        const size_t k = size_t(r) * t.width + c2;
        EXPECT_EQ(t.grad[k], 0.0f);
        if (fresh[r]) {
          EXPECT_EQ(t.adam_m[k], 0.0f) << param_name(Param(p)) << " row " << r;
          EXPECT_EQ(t.adam_v[k], 0.0f);
        } else {
          EXPECT_FLOAT_EQ(t.adam_m[k], t.value[k] + 1000.0f) << param_name(Param(p)) << " row " << r;
          EXPECT_FLOAT_EQ(t.adam_v[k], t.value[k] + 2000.0f);
        }
        const bool resampled = src[r] == 1 && (Param(p) == Param::Position || Param(p) == Param::LogScale);
        if (!resampled) {
          const float expect = float(src[r]) + 0.01f * float(c2) + 0.001f * float(p);
          if (Param(p) == Param::Sh || Param(p) == Param::ExtraLogit || Param(p) == Param::Position)
            EXPECT_FLOAT_EQ(t.value[k], expect) << param_name(Param(p)) << " row " << r;
        }
      }
  }
  // Clones are identical to their parents; split children are shrunk by 1.6 and displaced.
  EXPECT_FLOAT_EQ(m.values(Param::LogScale)[4 * 3], std::log(0.05f));
  for (int r : {5, 6}) {
    EXPECT_NEAR(m.values(Param::LogScale)[r * 3], std::log(0.5f / 1.6f), 1e-6f);
    EXPECT_NEAR(kernels::sigmoid(m.values(Param::OpacityLogit)[r]), 0.5f, 1e-6f);
  }
  const float* pos = m.values(Param::Position);
  const glm::vec3 parent(1.0f, 1.01f, 1.02f), c5(pos[15], pos[16], pos[17]), c6(pos[18], pos[19], pos[20]);
  EXPECT_GT(glm::length(c5 - parent), 1e-4f);
  EXPECT_GT(glm::length(c5 - c6), 1e-4f);
  EXPECT_LT(glm::length(c5 - parent), 0.5f * 6);  // within 6 sigma
}

TEST(Densify, SplitSamplesAreDeterministicAndGaussian) {
  // Many splits of one large Gaussian: the children's offsets have the parent's covariance.
  const size_t n = 4000;
  GaussianModel m = tagged_model(n);
  DensifyStats stats;
  stats.reset(n, Device::CPU);
  for (size_t i = 0; i < n; ++i) {
    set_gaussian(m, i, 0.0f, 0.5f);
    m.values(Param::LogScale)[i * 3 + 1] = std::log(2.0f);  // scales (1, 2, 1)
    for (int a = 0; a < 3; ++a) m.values(Param::Position)[i * 3 + a] = 0.0f;
    stats.grad_accum[i] = 1.0f;
    stats.denom[i] = 1.0f;
  }
  GaussianModel m2 = m.copy_to(Device::CPU);
  DensifySettings s;
  densify_and_prune(m, stats, s, 1.0f, false, 7);
  densify_and_prune(m2, stats, s, 1.0f, false, 7);
  ASSERT_EQ(m.count(), 2 * n);
  EXPECT_EQ(m.tensor(Param::Position).value.to_host(), m2.tensor(Param::Position).value.to_host());
  double sum[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
  for (size_t r = 0; r < 2 * n; ++r)
    for (int a = 0; a < 3; ++a) {
      const double x = m.values(Param::Position)[r * 3 + a];
      sum[a] += x;
      sq[a] += x * x;
    }
  const double expect_var[3] = {1, 4, 1};
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(sum[a] / (2 * n), 0.0, 0.06);
    EXPECT_NEAR(sq[a] / (2 * n), expect_var[a], 0.12 * expect_var[a]);
  }
}

TEST(Densify, PruneLargeAfterReset) {
  GaussianModel m = tagged_model(4);
  set_gaussian(m, 0, std::log(0.05f), 0.5f);  // fine
  set_gaussian(m, 1, std::log(0.05f), 0.5f);  // large on screen
  set_gaussian(m, 2, std::log(2.0f), 0.5f);   // large in the world (> 0.1 x extent 10)
  set_gaussian(m, 3, std::log(3.0f), 0.5f);   // large, high gradient: children (3 / 1.6) still too large
  DensifyStats stats;
  stats.reset(4, Device::CPU);
  for (int i = 0; i < 4; ++i) stats.denom[i] = 1;
  stats.max_radii[1] = 25;
  stats.grad_accum[3] = 1.0f;
  DensifySettings s;
  GaussianModel keep_all = m.copy_to(Device::CPU);
  DensifyCounts c = densify_and_prune(keep_all, stats, s, 10.0f, false, 1);
  EXPECT_EQ(c.after, 5u);  // 0, 1, 2 and two children of 3
  c = densify_and_prune(m, stats, s, 10.0f, true, 1);
  EXPECT_EQ(c.after, 1u);
  EXPECT_EQ(c.pruned, 4u);  // 1, 2 and both children of 3
  EXPECT_FLOAT_EQ(m.values(Param::Sh)[0], 0.004f);
}

TEST(Densify, StatisticsAndNdcScale) {
  DensifyStats s;
  s.reset(3, Device::CPU);
  const float norms[3] = {1.0f, 2.0f, 3.0f};
  const std::int32_t radii[3] = {4, 0, 7};
  s.add_view(norms, radii, 0.5f, 3, Device::CPU);
  s.add_view(norms, radii, 0.5f, 3, Device::CPU);
  EXPECT_FLOAT_EQ(s.grad_accum[0], 1.0f);
  EXPECT_FLOAT_EQ(s.grad_accum[1], 0.0f);
  EXPECT_FLOAT_EQ(s.denom[2], 2.0f);
  EXPECT_FLOAT_EQ(s.max_radii[2], 7.0f);
  EXPECT_FLOAT_EQ(ndc_gradient_scale(200, 200), 100.0f);
  EXPECT_THROW(s.add_view(norms, radii, 1.0f, 2, Device::CPU), Error);
}

TEST(Densify, PruneMaskAndOpacityReset) {
  GaussianModel m = tagged_model(5);
  const size_t removed = prune_gaussians(m, {1, 0, 1, 0, 1});
  EXPECT_EQ(removed, 2u);
  ASSERT_EQ(m.count(), 3u);
  const float expect_rows[3] = {0, 2, 4};
  for (int r = 0; r < 3; ++r) {
    EXPECT_FLOAT_EQ(m.values(Param::Position)[r * 3], expect_rows[r]);
    EXPECT_FLOAT_EQ(m.tensor(Param::Sh).adam_v[r * 48 + 5], m.values(Param::Sh)[r * 48 + 5] + 2000.0f);
  }
  EXPECT_THROW(prune_gaussians(m, {1, 0}), Error);
  m.values(Param::OpacityLogit)[0] = kernels::logit(0.001f);
  m.values(Param::OpacityLogit)[1] = kernels::logit(0.9f);
  reset_opacity(m, 0.01f);
  EXPECT_NEAR(kernels::sigmoid(m.values(Param::OpacityLogit)[0]), 0.001f, 1e-6f);
  EXPECT_NEAR(kernels::sigmoid(m.values(Param::OpacityLogit)[1]), 0.01f, 1e-6f);
  EXPECT_EQ(m.tensor(Param::OpacityLogit).adam_m[1], 0.0f);
  EXPECT_NE(m.tensor(Param::Position).adam_m[1], 0.0f);
}
