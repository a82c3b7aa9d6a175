// The scene model: activation chain of the extras (double-precision finite differences of the shared
// kernels, and the model's float path against them), initialisation (nearest neighbours, values), the
// Mip-Splatting 3D filter and the PLY round trip.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/io/ply.h"
#include "core/scene/filter3d.h"
#include "core/scene/gaussian_init.h"
#include "core/scene/gaussian_kernels.h"
#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "tests/support/model_values.h"
#include "tests/support/test_scenes.h"
#include "tests/support/test_support.h"
#include "train/run/train_setup.h"

using namespace goris;

namespace {

GaussianModel random_model(size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-2, 2);
  GaussianModel m(Device::CPU);
  m.allocate(n);
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = m.tensor(Param(p));
    for (size_t i = 0; i < t.value.size(); ++i) t.value[i] = u(rng);
  }
  return m;
}

Camera look_at_camera(glm::vec3 eye, glm::vec3 target, int w, int h, float f) {
  Camera c = goris::test::look_at(eye, target, w, 90.0f);  // the pose; then the requested intrinsics
  c.width = w;
  c.height = h;
  c.fx = c.fy = f;
  c.cx = w * 0.5f;
  c.cy = h * 0.5f;
  return c;
}

}  // namespace

TEST(ExtrasActivation, KernelGradientMatchesFiniteDifferences) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-4, 4);
  for (int trial = 0; trial < 50; ++trial) {
    const double x = u(rng), upstream = u(rng);
    double act = 0, act_grad = upstream, logit_grad = 0.25;
    kernels::extras_forward<double>(&x, &act, 0);
    kernels::extras_backward<double>(&act, &act_grad, &logit_grad, 0);
    const double h = 1e-6;
    double ap = 0, am = 0;
    const double xp = x + h, xm = x - h;
    kernels::extras_forward<double>(&xp, &ap, 0);
    kernels::extras_forward<double>(&xm, &am, 0);
    EXPECT_NEAR(logit_grad - 0.25, upstream * (ap - am) / (2 * h), 1e-9);
    EXPECT_EQ(act_grad, 0.0) << "the activated-space gradient is consumed";
  }
}

TEST(ExtrasActivation, ModelViewAndBackprop) {
  GaussianModel m = random_model(17, 2);
  const GaussianView v = m.view(true);
  ASSERT_EQ(v.n_extras, extra::kCount);
  ASSERT_EQ(v.count, 17);
  const float* logits = m.values(Param::ExtraLogit);
  for (size_t i = 0; i < 17 * extra::kCount; ++i)
    EXPECT_NEAR(v.extras[i], 1.0 / (1.0 + std::exp(-double(logits[i]))), 1e-6);
  GaussianGradView g = m.grad_view(true);
  ASSERT_NE(g.extras, nullptr);
  for (size_t i = 0; i < 17 * extra::kCount; ++i) g.extras[i] = float(i % 5) - 2.0f;
  m.backprop_extras();
  const float* lg = m.tensor(Param::ExtraLogit).grad.data();
  for (size_t i = 0; i < 17 * extra::kCount; ++i) {
    const double s = v.extras[i];
    EXPECT_NEAR(lg[i], (double(i % 5) - 2.0) * s * (1 - s), 1e-6);
    EXPECT_EQ(g.extras[i], 0.0f);
  }
  m.zero_grad();
  for (size_t i = 0; i < 17 * extra::kCount; ++i) EXPECT_EQ(lg[i], 0.0f);
  // Without extras the renderers blend none.
  EXPECT_EQ(m.view(false).n_extras, 0);
  EXPECT_EQ(m.view(false).extras, nullptr);
  EXPECT_EQ(m.grad_view(false).extras, nullptr);
}

TEST(ExtrasActivation, DiffuseFollowsTheShColoursViewIndependentPart) {
  // diffuse = C0 x DC + 1/2 per channel (clamped inside (0, 1)); the other extras and the SH stay as they were.
  GaussianModel m = random_model(40, 5);
  float* sh = m.values(Param::Sh);
  const int sw = param_width(Param::Sh);
  sh[0] = 10.0f;   // colour 3.3: clamped to 1 - 1e-3
  sh[1] = -10.0f;  // -2.3: clamped to 1e-3
  const std::vector<float> sh_before = m.tensor(Param::Sh).value.to_host();
  const std::vector<float> extras_before = m.tensor(Param::ExtraLogit).value.to_host();
  m.derive_diffuse_from_sh();
  const GaussianView v = m.view(true);
  for (size_t i = 0; i < 40; ++i)
    for (int k = 0; k < extra::kCount; ++k) {
      const size_t e = i * extra::kCount + size_t(k);
      if (k >= extra::kDiffuse && k < extra::kDiffuse + 3) {
        const double col = 0.28209479177387814 * sh[i * size_t(sw) + size_t(k - extra::kDiffuse)] + 0.5;
        EXPECT_NEAR(v.extras[e], std::clamp(col, 1e-3, 1 - 1e-3), 1e-5) << i << " " << k;
      } else {
        EXPECT_EQ(m.values(Param::ExtraLogit)[e], extras_before[e]) << i << " " << k;
      }
    }
  EXPECT_NEAR(v.extras[extra::kDiffuse], 1 - 1e-3, 1e-6);
  EXPECT_NEAR(v.extras[extra::kDiffuse + 1], 1e-3, 1e-6);
  EXPECT_EQ(m.tensor(Param::Sh).value.to_host(), sh_before);
}

TEST(ShDcColour, HelperPairIsTheBandZeroBasisAndRoundTrips) {
  // colour = C0 x DC + 1/2 with C0 = 1 / (2 sqrt(pi)), written here independently of the helpers.
  const double c0 = 0.5 / std::sqrt(3.14159265358979323846);
  for (double dc : {-1.77, 0.0, 0.3, 2.5}) {
    EXPECT_NEAR(kernels::colour_from_sh_dc(dc), c0 * dc + 0.5, 1e-7);  // C0 is a float
    EXPECT_NEAR(kernels::sh_dc_from_colour(kernels::colour_from_sh_dc(dc)), dc, 1e-6);
  }
  const glm::vec3 rgb(0.1f, 0.5f, 0.9f);
  const glm::vec3 back = kernels::colour_from_sh_dc(kernels::sh_dc_from_colour(rgb));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], rgb[c], 1e-6f);
  EXPECT_EQ(kernels::sh_dc_from_colour(0.5f), 0.0f);
}

TEST(KnnMeanDistance, MatchesBruteForce) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<glm::vec3> pts(700);
  for (auto& p : pts) p = glm::vec3(u(rng), u(rng) * 0.1f, u(rng));  // flattened: an uneven tree
  pts[5] = pts[4];                                                   // a duplicate
  const std::vector<float> d = knn_mean_distance(pts, 3);
  for (size_t i = 0; i < pts.size(); ++i) {
    std::vector<double> d2;
    for (size_t j = 0; j < pts.size(); ++j)
      if (j != i) d2.push_back(glm::dot(pts[i] - pts[j], pts[i] - pts[j]));
    std::partial_sort(d2.begin(), d2.begin() + 3, d2.end());
    EXPECT_NEAR(d[i], std::sqrt((d2[0] + d2[1] + d2[2]) / 3), 1e-6) << i;
  }
  EXPECT_EQ(knn_mean_distance({glm::vec3(1)}, 3), std::vector<float>{0.0f});
  EXPECT_NEAR(knn_mean_distance({glm::vec3(0), glm::vec3(3, 4, 0)}, 3)[0], 5.0f, 1e-6f);
}

TEST(GaussianInit, FromPoints) {
  std::vector<glm::vec3> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  std::vector<glm::vec3> cols(pts.size(), glm::vec3(0.75f, 0.5f, 0.25f));
  GaussianModel m = init_from_points(pts, cols, Device::CPU);
  ASSERT_EQ(m.count(), 5u);
  EXPECT_EQ(m.sh_degree, 0);
  const float* ls = m.values(Param::LogScale);
  const std::vector<float> d = knn_mean_distance(pts, 3);
  for (int i = 0; i < 5; ++i)
    for (int a = 0; a < 3; ++a) EXPECT_FLOAT_EQ(ls[i * 3 + a], std::log(d[i]));
  EXPECT_FLOAT_EQ(m.values(Param::Rotation)[4], 1.0f);
  EXPECT_NEAR(kernels::sigmoid(m.values(Param::OpacityLogit)[0]), 0.1f, 1e-6f);
  const float* sh = m.values(Param::Sh);
  EXPECT_NEAR(0.28209479f * sh[0] + 0.5f, 0.75f, 1e-6f);
  EXPECT_NEAR(0.28209479f * sh[2] + 0.5f, 0.25f, 1e-6f);
  EXPECT_EQ(sh[3], 0.0f);
  const float* ex = m.values(Param::ExtraLogit);
  EXPECT_NEAR(kernels::sigmoid(ex[extra::kRegion]), 0.9f, 1e-6f);
  EXPECT_NEAR(kernels::sigmoid(ex[extra::kDiffuse]), 0.5f, 1e-6f);
  EXPECT_THROW(init_from_points({}, {}, Device::CPU), Error);
}

TEST(GaussianInit, RandomBoxFromCameras) {
  std::vector<Camera> cams;
  for (int k = 0; k < 8; ++k) {
    const float a = 6.2831853f * k / 8;
    cams.push_back(look_at_camera(glm::vec3(4 * std::cos(a), 4 * std::sin(a), 1.0f), glm::vec3(0.2f, -0.1f, 0.0f), 64,
                                  64, 60));
  }
  const Box box = box_from_cameras(cams);
  const glm::vec3 c = (box.lo + box.hi) * 0.5f;
  EXPECT_NEAR(c.x, 0.2f, 0.05f);
  EXPECT_NEAR(c.y, -0.1f, 0.05f);
  EXPECT_NEAR(c.z, 0.0f, 0.05f);
  EXPECT_NEAR(box.hi.x - c.x, 0.33f * std::sqrt(16.0f + 1.0f), 0.1f);
  std::vector<glm::vec3> p1, c1, p2, c2;
  random_points(box, 100, 9, p1, c1);
  random_points(box, 100, 9, p2, c2);
  EXPECT_EQ(p1, p2);
  for (const auto& p : p1)
    for (int a = 0; a < 3; ++a) EXPECT_TRUE(p[a] >= box.lo[a] && p[a] <= box.hi[a]);
  for (const auto& col : c1)  // 3DGS: SH DC in [0, 1/255], so mid grey
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(col[c] >= 0.5f && col[c] <= 0.5f + kernels::kShC0 / 255.0f) << col[c];
}

// intrinsic_env_distance puts the environment on a sphere around what the cameras look at, once: the
// resolved centre and radius are what the run keeps; 0 leaves it at infinity.
TEST(GaussianInit, EnvironmentSphereAroundWhatTheCamerasLookAt) {
  Dataset ds;
  for (int k = 0; k < 8; ++k) {
    const float a = 6.2831853f * k / 8;
    View v;
    v.camera = look_at_camera(glm::vec3(4 * std::cos(a), 4 * std::sin(a), 1.0f), glm::vec3(0.2f, -0.1f, 0.0f), 64, 64, 60);
    ds.train.push_back(v);
  }
  TrainConfig config;
  EXPECT_EQ(config.intrinsic.env_distance, 1.0f) << "on a sphere by default";
  config.intrinsic.env_distance = 0.0f;
  resolve_environment_sphere(ds, config);
  EXPECT_EQ(config.intrinsic.env_radius, 0.0f);
  config.intrinsic.env_distance = 1.5f;
  resolve_environment_sphere(ds, config);
  EXPECT_NEAR(config.intrinsic.env_center.x, 0.2f, 0.05f);
  EXPECT_NEAR(config.intrinsic.env_center.y, -0.1f, 0.05f);
  EXPECT_NEAR(config.intrinsic.env_center.z, 0.0f, 0.05f);
  EXPECT_NEAR(config.intrinsic.env_radius, 1.5f * std::sqrt(16.0f + 1.0f), 0.1f);
  const float radius = config.intrinsic.env_radius;
  config.intrinsic.env_distance = 3.0f;  // a resumed run keeps its sphere
  resolve_environment_sphere(ds, config);
  EXPECT_EQ(config.intrinsic.env_radius, radius);
  config.intrinsic.env_distance = -1.0f;
  EXPECT_THROW(config.validate("test"), Error);
}

TEST(Filter3d, HighestSamplingRateOfTheCamerasThatSee) {
  GaussianModel m = random_model(3, 4);
  float* pos = m.values(Param::Position);
  const float xyz[9] = {0, 0, 0, 0, 0, 1.5f, 50, 0, 0};  // near both, closer to camera A, seen by none
  std::copy(xyz, xyz + 9, pos);
  const Camera a = look_at_camera(glm::vec3(0, 0, 4), glm::vec3(0), 64, 64, 100);
  const Camera b = look_at_camera(glm::vec3(0, -6, 0.01f), glm::vec3(0), 64, 64, 100);
  compute_filter3d(m, {a, b});
  ASSERT_EQ(m.filter3d_var.size(), 3u);
  EXPECT_NEAR(m.filter3d_var[0], 0.2f * (4.0f / 100) * (4.0f / 100), 1e-7f);  // camera A: z = 4
  EXPECT_NEAR(m.filter3d_var[1], 0.2f * (2.5f / 100) * (2.5f / 100), 1e-7f);
  // Unseen: the lowest rate among the seen ones (Mip-Splatting gives them the largest distance).
  EXPECT_NEAR(m.filter3d_var[2], m.filter3d_var[0], 1e-9f);
  EXPECT_NE(m.view(false).filter3d_var, nullptr);
}

TEST(GaussianPlyConversion, RoundTripIsExact) {
  GaussianModel m = random_model(11, 5);
  m.sh_degree = 1;
  const GaussianPly ply = m.to_ply();
  EXPECT_EQ(ply.sh_degree, 3);
  ASSERT_NE(ply.extra("fresnel_2"), nullptr);
  EXPECT_EQ((*ply.extra("label"))[4], m.values(Param::ExtraLogit)[4 * extra::kCount + extra::kLabel]);
  const auto dir = test::scratch_dir("scene_model_ply");
  write_ply(dir / "m.ply", ply);
  GaussianModel back = GaussianModel::from_ply(read_ply(dir / "m.ply"), Device::CPU);
  ASSERT_EQ(back.count(), 11u);
  for (int p = 0; p < kParamCount; ++p)
    EXPECT_EQ(back.tensor(Param(p)).value.to_host(), m.tensor(Param(p)).value.to_host()) << param_name(Param(p));
}

TEST(GaussianPlyConversion, MissingExtrasTakeInitialValues) {
  GaussianModel m = random_model(4, 6);
  GaussianPly ply = m.to_ply();
  ply.extras.clear();
  ply.sh_degree = 0;
  ply.f_rest.clear();
  GaussianModel back = GaussianModel::from_ply(ply, Device::CPU);
  EXPECT_EQ(back.sh_degree, 0);
  EXPECT_NEAR(kernels::sigmoid(back.values(Param::ExtraLogit)[extra::kRegion]), 0.9f, 1e-6f);
  EXPECT_EQ(back.values(Param::Sh)[5], 0.0f);
  EXPECT_EQ(back.values(Param::Sh)[1], m.values(Param::Sh)[1]);
  // A standard 3DGS PLY has no diffuse channel: it shows the SH colour's view-independent part, not grey.
  EXPECT_LT(test::diffuse_vs_sh_colour(back).max_error, 1e-5);
  EXPECT_NEAR(kernels::sigmoid(back.values(Param::ExtraLogit)[extra::kFresnel]), 0.5f, 1e-6f);
}
