// GORIS_CUDA_CALL (core/compute/cuda_dispatch.h): with the CUDA backend it makes the driver call; a build
// without it answers a CUDA device with a goris::Error that names the module, the driver never called.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/compute/cuda_dispatch.h"
#include "render/raster/rasterizer.h"
#include "render/trace/gaussian_tracer.h"
#include "tests/support/test_support.h"
#include "train/intrinsic/intrinsic_glue.h"

namespace goris {
namespace {

const std::string kNoBackend = ": CUDA device requested but this build has no CUDA backend";

TEST(CudaDispatch, CallsTheDriverOrNamesTheModule) {
  int calls = 0;
  auto driver = [&calls](int x) {
    ++calls;
    return 2 * x;
  };
  if (cuda_compiled()) {
    EXPECT_EQ(GORIS_CUDA_CALL("widget", driver(21)), 42);
    EXPECT_EQ(calls, 1);
  } else {
    test::expect_error([&] { GORIS_CUDA_CALL("widget", driver(21)); }, "widget" + kNoBackend);
    EXPECT_EQ(calls, 0);
  }
}

TEST(CudaDispatch, CpuOnlyBuildNamesTheModule) {
  if (cuda_compiled()) GTEST_SKIP() << "this build has the CUDA backend";
  std::vector<float> pos = {0, 0, 3}, ls = {-2, -2, -2}, rot = {1, 0, 0, 0}, op = {0}, sh(48, 0.f);
  GaussianView v;
  v.count = 1, v.positions = pos.data(), v.log_scales = ls.data(), v.rotations = rot.data();
  v.opacity_logits = op.data(), v.sh = sh.data();
  Camera cam;
  cam.width = 16, cam.height = 12;
  cam.fx = cam.fy = 20, cam.cx = 8, cam.cy = 6;
  test::expect_error([&] { rasterize(v, cam, RasterSettings{}, Device::CUDA); }, "rasterizer" + kNoBackend);
  test::expect_error([] { GaussianTracer tracer(Device::CUDA); }, "tracer" + kNoBackend);
  test::expect_error([] { intrinsic_glue::net_input(Device::CUDA, nullptr, nullptr, nullptr, nullptr, 0, 1, nullptr); },
                     "intrinsic renderer" + kNoBackend);
}

}  // namespace
}  // namespace goris
