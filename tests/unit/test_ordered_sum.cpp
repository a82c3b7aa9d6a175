// Scatter-add in a fixed order (core/compute/ordered_sum.h) and the environment map's texel gradients built
// on it: the sums equal a serial loop bit for bit, whatever the rows' positions, and keys that do not fit
// are refused. (The CUDA tests check the same code on the GPU.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "core/compute/ordered_sum.h"
#include "core/util/error.h"
#include "render/envmap/cube_map_ops.h"
#include "render/envmap/deferred_texel_grads.h"

using namespace goris;

namespace {

struct Rows {
  std::vector<std::uint32_t> target, order;  // target == targets: an unused row
  std::vector<float> values;                 // [n][width]
};

Rows random_rows(std::size_t n, std::uint32_t targets, int width, std::mt19937& rng) {
  Rows r;
  std::uniform_int_distribution<std::uint32_t> pick(0, targets);  // targets itself: unused
  std::uniform_real_distribution<float> value(-1e3f, 1e3f), scale(-8.f, 8.f);
  std::vector<std::uint32_t> orders(n);
  std::iota(orders.begin(), orders.end(), 0u);
  std::shuffle(orders.begin(), orders.end(), rng);
  for (std::size_t i = 0; i < n; ++i) {
    r.target.push_back(pick(rng));
    r.order.push_back(orders[i]);
    for (int c = 0; c < width; ++c) r.values.push_back(value(rng) * std::exp2(scale(rng)));  // wide range: order matters
  }
  return r;
}

// The sums add_rows_in_key_order must reproduce: per target, its rows in increasing order, one by one.
std::vector<float> serial_sums(const Rows& r, std::uint32_t targets, int width, std::vector<float> out) {
  std::vector<std::size_t> idx(r.target.size());
  std::iota(idx.begin(), idx.end(), 0u);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return r.order[a] < r.order[b]; });
  for (std::size_t i : idx)
    if (r.target[i] < targets)
      for (int c = 0; c < width; ++c) out[r.target[i] * width + c] += r.values[i * width + c];
  return out;
}

std::vector<float> ordered_sums(const Rows& r, std::uint32_t targets, int width, std::vector<float> out) {
  const OrderedKeyLayout layout(targets, r.target.size());
  Buffer<std::uint64_t> keys(r.target.size(), Device::CPU);
  for (std::size_t i = 0; i < r.target.size(); ++i)
    keys[i] = r.target[i] < targets ? layout.key(r.target[i], r.order[i]) : layout.unused();
  add_rows_in_key_order(layout, keys, r.values.data(), width, out.data());
  return out;
}

}  // namespace

TEST(OrderedSum, EqualsASerialLoopBitForBit) {
  std::mt19937 rng(3);
  const std::uint32_t targets = 37;
  const int width = 5;
  const Rows r = random_rows(20000, targets, width, rng);
  std::vector<float> start(targets * width);
  for (float& v : start) v = std::uniform_real_distribution<float>(-1, 1)(rng);
  const std::vector<float> want = serial_sums(r, targets, width, start);
  const std::vector<float> got = ordered_sums(r, targets, width, start);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], want[i]) << "element " << i;

  // The same rows written at other positions (as racing threads would write them): the same bits.
  std::vector<std::size_t> perm(r.target.size());
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  Rows moved;
  for (std::size_t i : perm) {
    moved.target.push_back(r.target[i]);
    moved.order.push_back(r.order[i]);
    for (int c = 0; c < width; ++c) moved.values.push_back(r.values[i * width + c]);
  }
  EXPECT_EQ(ordered_sums(moved, targets, width, start), got);

  // And the order does change the float sums, so the test above can fail.
  Rows reversed = r;
  for (auto& o : reversed.order) o = std::uint32_t(r.order.size() - 1 - o);
  EXPECT_NE(ordered_sums(reversed, targets, width, start), got);
}

TEST(OrderedSum, EmptyAndUnusedRowsAddNothing) {
  std::vector<float> out = {1.f, 2.f};
  Buffer<std::uint64_t> none(0, Device::CPU);
  add_rows_in_key_order(OrderedKeyLayout(2, 1), none, static_cast<const float*>(nullptr), 1, out.data());
  const OrderedKeyLayout layout(2, 3);
  Buffer<std::uint64_t> keys(std::vector<std::uint64_t>{layout.unused(), layout.key(1, 2), layout.unused()},
                             Device::CPU);
  const std::vector<float> rows = {100.f, 0.5f, 100.f};
  add_rows_in_key_order(layout, keys, rows.data(), 1, out.data());
  EXPECT_EQ(out, (std::vector<float>{1.f, 2.5f}));
}

TEST(OrderedSum, RefusesKeysWiderThan64Bits) {
  EXPECT_NO_THROW(OrderedKeyLayout(1ull << 31, 1ull << 32));
  EXPECT_THROW(OrderedKeyLayout(1ull << 40, 1ull << 30), Error);
}

// The texel gradients of many lookups, summed by flush(), equal the serial loop over the lookups' taps.
TEST(OrderedSum, TexelGradientsEqualASerialLoopOverThePixels) {
  using envmap::Vec3;
  constexpr int R = 8, L = 4;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1), u01(0, 1);
  std::vector<float> chain(std::size_t(envmap::chain_size(R, L)));
  for (float& v : chain) v = 0.1f + u01(rng);
  const envmap::CubeMipsT<float> mips{chain.data(), R, L};
  const std::size_t n = 3000;
  std::vector<Vec3<float>> dirs, douts;
  std::vector<float> rough;
  for (std::size_t i = 0; i < n; ++i) {
    dirs.emplace_back(u(rng), u(rng), u(rng));
    rough.push_back(u01(rng));
    douts.push_back(i % 7 == 0 ? Vec3<float>(0.f) : Vec3<float>(u(rng), u(rng), u(rng)) * 100.f);
  }
  std::vector<float> want(chain.size(), 0.25f), got = want;
  for (std::size_t i = 0; i < n; ++i) {
    if (douts[i] == Vec3<float>(0.f)) continue;
    const envmap::LookupTaps<float> taps = envmap::lookup_taps(mips, dirs[i], rough[i]);
    for (int t = 0; t < taps.n; ++t)
      for (int ch = 0; ch < 3; ++ch) want[std::size_t(taps.idx[t]) + ch] += taps.w[t] * douts[i][ch];
  }
  envmap::DeferredTexelGrads<float> texels(Device::CPU, got.data(), n);
  for (std::size_t i = 0; i < n; ++i) decltype(texels)::record(texels.records(), i, dirs[i], rough[i], douts[i]);
  texels.flush(mips);
  for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], want[i]) << "texel value " << i;
}
