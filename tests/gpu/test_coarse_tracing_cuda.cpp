// Coarse tracing's selection passes on CUDA against the CPU on the same rays and screen roughness: both
// passes' selections, the gathered rays, the net's distance input and the filter's mass must be identical
// (integer decisions, one float division). Skipped (with a message) where no CUDA device is present.
#include <random>
#include <vector>

#include "tests/support/test_support.h"
#include "train/intrinsic/coarse_tracing.h"

using namespace goris;

namespace {

struct Result {
  std::vector<std::uint32_t> first_keep, all_keep, pixels;
  std::vector<float> origins, distance, mass;
};

Result run(Device d, int W, int H, const std::vector<std::uint32_t>& pix, const std::vector<float>& org,
           const std::vector<float>& rs_host) {
  ReflectionRays rays;
  rays.pixels = Buffer<std::uint32_t>(pix, d);
  rays.origins = Buffer<float>(org, d);
  rays.directions = Buffer<float>(org, d);
  rays.count = pix.size();
  const CoarseTracingSettings cs{2, 5};
  const RaySelection first = select_block_rays(rays, W, H, nullptr, cs);
  const Buffer<float> rs(rs_host, d);
  const RaySelection all = select_block_rays(rays, W, H, &rs, cs);
  const RaySelection added = selection_difference(all, first);
  ReflectionRays out;
  out.pixels = Buffer<std::uint32_t>(all.count, d);
  out.origins = Buffer<float>(3 * all.count, d);
  out.directions = Buffer<float>(3 * all.count, d);
  out.count = all.count;
  gather_rays(rays, first, out, 0);
  gather_rays(rays, added, out, first.count);
  std::vector<float> depth(first.count), alpha(first.count);
  for (std::size_t j = 0; j < first.count; ++j) depth[j] = 0.1f * float(j), alpha[j] = j % 3 ? 0.7f : 0.0f;
  Result r;
  r.first_keep = first.keep.to_host();
  r.all_keep = all.keep.to_host();
  r.pixels = out.pixels.to_host();
  r.origins = out.origins.to_host();
  r.distance = representative_distance(rays, &first, Buffer<float>(depth, d), Buffer<float>(alpha, d), W, H, 2, 3.0f)
                   .to_host();
  r.mass = selection_mass(rays, all, W, H).to_host();
  return r;
}

TEST(CoarseTracingCuda, SelectionMatchesCpu) {
  GORIS_REQUIRE_GPU();
  const int W = 203, H = 157;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<std::uint32_t> pix;
  std::vector<float> org, rs(std::size_t(W) * H);
  for (std::size_t p = 0; p < rs.size(); ++p) {
    rs[p] = u(rng);
    if (u(rng) < 0.8f) {
      pix.push_back(std::uint32_t(p));
      for (int c = 0; c < 3; ++c) org.push_back(float(p) + c);
    }
  }
  const Result a = run(Device::CPU, W, H, pix, org, rs), b = run(Device::CUDA, W, H, pix, org, rs);
  EXPECT_EQ(a.first_keep, b.first_keep);
  EXPECT_EQ(a.all_keep, b.all_keep);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_EQ(a.origins, b.origins);
  EXPECT_EQ(a.mass, b.mass);
  ASSERT_EQ(a.distance.size(), b.distance.size());
  for (std::size_t p = 0; p < a.distance.size(); ++p) ASSERT_FLOAT_EQ(a.distance[p], b.distance[p]) << p;
}

}  // namespace
