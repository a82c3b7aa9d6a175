// Distillation (export/distill/distill.h) on a tiny synthetic scene: a teacher with a strongly view-dependent
// appearance (degree-3 SH) is distilled into a student that starts from the same geometry with plain
// colours only (as an intrinsic run's D starts); the held-out PSNR must rise substantially while the
// geometry of the baked PLY stays bit for bit the start's. Also: no training, stops, learning geometry on
// request, and bad input.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "core/compute/memory.h"
#include "core/scene/filter3d.h"
#include "core/util/error.h"
#include "export/distill/distill.h"
#include "export/frames/camera_path.h"
#include "tests/support/test_support.h"
#include "train/radiance/raster_renderer.h"

using namespace goris;

namespace {

constexpr int kSize = 32;

Camera intrinsics() {
  const float f = 0.5f * kSize / std::tan(glm::radians(25.0f));  // 50 degrees
  return Camera{.width = kSize, .height = kSize, .fx = f, .fy = f, .cx = 0.5f * kSize, .cy = 0.5f * kSize};
}

// Cameras at distance 3.5 around the origin on two rings (heights 0.8 and 2.0), `n` per ring.
std::vector<Camera> cameras(int n, float phase) {
  std::vector<Camera> out;
  for (float h : {0.8f, 2.0f})
    for (int k = 0; k < n; ++k) {
      const float a = phase + 6.2831853f * float(k) / float(n);
      const float r = std::sqrt(3.5f * 3.5f - h * h);
      out.push_back(look_at_camera(intrinsics(), glm::vec3(r * std::cos(a), r * std::sin(a), h), glm::vec3(0.0f),
                                   glm::vec3(0, 0, 1)));
    }
  return out;
}

// A blob of Gaussians; `view_dependent`: SH degree 3 with large higher coefficients, else degree 0 with
// the same base colours.
GaussianModel scene(bool view_dependent) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  const int n = 150;
  GaussianModel m(Device::CPU);
  m.allocate(n);
  for (int i = 0; i < n; ++i) {
    glm::vec3 p(u(rng), u(rng), u(rng));
    p = 0.8f * glm::normalize(p) * std::cbrt(0.5f + 0.5f * u(rng));
    for (int a = 0; a < 3; ++a) {
      m.values(Param::Position)[i * 3 + a] = p[a];
      m.values(Param::LogScale)[i * 3 + a] = std::log(0.14f + 0.04f * u(rng));
    }
    float* q = m.values(Param::Rotation) + i * 4;
    for (int k = 0; k < 4; ++k) q[k] = u(rng) + (k == 0 ? 2.0f : 0.0f);
    m.values(Param::OpacityLogit)[i] = 2.0f + 0.5f * u(rng);
    float* sh = m.values(Param::Sh) + i * 48;
    for (int k = 0; k < 48; ++k) {
      const float v = u(rng);
      sh[k] = k < 3 ? 0.8f * v : view_dependent ? (k < 12 ? 0.35f : 0.15f) * v : 0.0f;
    }
    for (int k = 0; k < extra::kCount; ++k) m.values(Param::ExtraLogit)[i * extra::kCount + k] = 0.0f;
  }
  m.sh_degree = view_dependent ? 3 : 0;
  m.max_sh_degree = 3;
  return m;
}

TrainConfig run_config() {
  TrainConfig c;
  c.device = DeviceChoice::CPU;
  c.input.background = glm::vec3(0.1f, 0.1f, 0.1f);
  return c;
}

std::vector<float> render(RasterRenderer& renderer, GaussianModel& model, const Camera& cam) {
  const RenderedImages r = renderer.forward(model.view(false), cam);
  return std::vector<float>(r.color, r.color + 3 * size_t(cam.width) * size_t(cam.height));
}

// The teacher: the view-dependent scene through the rasterizer.
struct Teacher {
  GaussianModel model = scene(true);
  RasterRenderer renderer{RasterRenderer::settings_for(run_config()), Device::CPU};
  int calls = 0;
  std::vector<float> operator()(const Camera& cam) {
    ++calls;
    return render(renderer, model, cam);
  }
};

GaussianModel start_model(const std::vector<Camera>& train) {
  GaussianModel m = scene(false);
  compute_filter3d(m, train);  // exercises the filter being kept and baked
  return m;
}

void expect_same_geometry(const GaussianPly& a, const GaussianPly& b) {
  ASSERT_EQ(a.count, b.count);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.scales, b.scales);
  EXPECT_EQ(a.rotations, b.rotations);
  EXPECT_EQ(a.opacity, b.opacity);
}

}  // namespace

TEST(ExportDistill, RaisesHeldOutPsnrAndKeepsTheGeometry) {
  const std::vector<Camera> train = cameras(12, 0.0f), holdout = cameras(3, 0.4f);
  const GaussianModel start = start_model(train);
  Teacher teacher;
  DistillSettings s;
  s.iterations = 1000;
  s.seed = 1;
  std::vector<std::string> phases;
  int last_iteration = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const DistillResult r = distill_to_sh(
      start, std::ref(teacher), run_config(), train, holdout, 3.5f, s, [&](const DistillProgress& p) {
        if (phases.empty() || phases.back() != p.phase) phases.push_back(p.phase);
        if (p.phase == "distilling") last_iteration = p.done;
      });
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("distil: %zu targets (%zu interpolated), %d iterations in %.2f s: held-out PSNR %.2f -> %.2f dB\n",
              r.target_views, r.extra_views, r.iterations, secs, r.psnr_start, r.psnr);

  EXPECT_EQ(r.iterations, 1000);
  EXPECT_FALSE(r.stopped);
  EXPECT_EQ(r.target_views, 48u);  // 24 training + 24 interpolated
  EXPECT_EQ(r.extra_views, 24u);
  EXPECT_EQ(r.holdout_views, 6u);
  EXPECT_EQ(teacher.calls, 48 + 6);
  EXPECT_EQ(phases, (std::vector<std::string>{"targets", "distilling", "held-out views"}));
  EXPECT_EQ(last_iteration, 1000);
  EXPECT_GT(r.psnr - r.psnr_start, 6.0) << "distillation should reproduce most of the view dependence";
  ASSERT_EQ(r.psnr_per_view.size(), 6u);

  // A standard SH-only model with exactly the start's geometry (3D filter folded in the same way).
  EXPECT_EQ(r.ply.sh_degree, 3);
  EXPECT_TRUE(r.ply.extras.empty());
  expect_same_geometry(r.ply, baked_sh_ply(start));
  EXPECT_NE(r.ply.f_rest, baked_sh_ply(start).f_rest) << "the view-dependent coefficients were not learned";
}

TEST(ExportDistill, NoIterationsBakesTheStartAsItIs) {
  const std::vector<Camera> train = cameras(4, 0.0f), holdout = cameras(2, 0.4f);
  const GaussianModel start = start_model(train);
  // The teacher is the start itself: the baked PLY (filter folded in) must render like it.
  RasterRenderer renderer(RasterRenderer::settings_for(run_config()), Device::CPU);
  GaussianModel copy = start.copy_to(Device::CPU);
  DistillTeacher teacher = [&](const Camera& cam) { return render(renderer, copy, cam); };
  DistillSettings s;
  s.iterations = 0;
  const DistillResult r = distill_to_sh(start, teacher, run_config(), train, holdout, 3.5f, s);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.target_views, 0u);
  EXPECT_TRUE(std::isinf(r.psnr_start)) << "the start renders exactly like the teacher: " << r.psnr_start;
  EXPECT_GT(r.psnr, 80.0) << "baking the 3D filter into scales and opacities should not change the image";
  expect_same_geometry(r.ply, baked_sh_ply(start));
  EXPECT_EQ(r.ply.f_dc, baked_sh_ply(start).f_dc);
}

TEST(ExportDistill, StopsEarlyWithACompleteResult) {
  const std::vector<Camera> train = cameras(4, 0.0f), holdout = cameras(2, 0.4f);
  Teacher teacher;
  std::atomic<bool> stop{true};
  DistillSettings s;
  s.iterations = 50;
  const DistillResult r = distill_to_sh(start_model(train), std::ref(teacher), run_config(), train, holdout, 3.5f, s, {}, &stop);
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.ply.count, 150u);
  EXPECT_TRUE(std::isfinite(r.psnr));
}

TEST(ExportDistill, GeometryLearnsOnlyWhenAsked) {
  const std::vector<Camera> train = cameras(4, 0.0f), holdout = cameras(2, 0.4f);
  const GaussianModel start = start_model(train);
  Teacher teacher;
  DistillSettings s;
  s.iterations = 20;
  s.geometry_lr_scale = 1.0f;
  const DistillResult r = distill_to_sh(start, std::ref(teacher), run_config(), train, holdout, 3.5f, s);
  EXPECT_NE(r.ply.positions, baked_sh_ply(start).positions);
  const TrainConfig frozen = distill_config(run_config(), DistillSettings{});
  EXPECT_EQ(frozen.lr.position_init, 0.0f);
  EXPECT_EQ(frozen.lr.opacity, 0.0f);
  EXPECT_EQ(frozen.lr.sh_dc, run_config().lr.sh_dc * DistillSettings{}.sh_lr_scale);
  EXPECT_EQ(frozen.lr.sh_rest, run_config().lr.sh_rest * DistillSettings{}.sh_lr_scale);
  EXPECT_EQ(frozen.mode, TrainMode::Radiance);
  EXPECT_EQ(frozen.sh.max_degree, 3);
}

TEST(ExportDistill, BadInput) {
  const std::vector<Camera> train = cameras(3, 0.0f), holdout = cameras(1, 0.4f);
  const GaussianModel start = start_model(train);
  DistillSettings s;
  s.iterations = 5;
  auto expect_error = [&](const DistillTeacher& teacher, const std::vector<Camera>& tr, const std::vector<Camera>& ho,
                          const DistillSettings& st, const std::string& needle) {
    try {
      distill_to_sh(start, teacher, run_config(), tr, ho, 3.5f, st);
      ADD_FAILURE() << "expected an error containing '" << needle << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  const DistillTeacher grey = [](const Camera& c) { return std::vector<float>(3 * size_t(c.width) * c.height, 0.5f); };
  const DistillTeacher small = [](const Camera&) { return std::vector<float>(12, 0.5f); };
  const DistillTeacher nan = [](const Camera& c) {
    std::vector<float> v(3 * size_t(c.width) * c.height, 0.5f);
    v[7] = std::nanf("");
    return v;
  };
  expect_error(small, train, holdout, s, "expected 3072");
  expect_error(nan, train, holdout, s, "non-finite");
  expect_error(grey, {}, holdout, s, "no training cameras");
  expect_error(grey, train, {}, s, "no held-out cameras");
  DistillSettings neg = s;
  neg.iterations = -1;
  expect_error(grey, train, holdout, neg, "iterations");
  DistillSettings bad_lr = s;
  bad_lr.geometry_lr_scale = -1;
  expect_error(grey, train, holdout, bad_lr, "learning-rate");
  DistillSettings bad_sh = s;
  bad_sh.sh_lr_scale = std::nanf("");
  expect_error(grey, train, holdout, bad_sh, "SH learning-rate scale");
  bad_sh.sh_lr_scale = 0;
  expect_error(grey, train, holdout, bad_sh, "SH learning-rate scale");
}
