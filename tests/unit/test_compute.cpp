// CPU compute primitives against plain sequential references, on random sizes including 0, 1 and
// non-powers of two.
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "core/compute/buffer.h"
#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "tests/support/test_support.h"

using namespace goris;

namespace {
const std::vector<std::size_t> kSizes = {0, 1, 2, 3, 7, 255, 256, 257, 1000, 4097, 65537, 300001};

std::vector<std::uint64_t> random_keys(std::size_t n, std::mt19937_64& rng, std::uint64_t mask) {
  std::vector<std::uint64_t> k(n);
  for (auto& x : k) x = rng() & mask;
  return k;
}
}  // namespace

TEST(Buffer, MoveResizeAndCopies) {
  Buffer<float> a(std::vector<float>{1, 2, 3}, Device::CPU);
  Buffer<float> b = std::move(a);
  EXPECT_EQ(a.size(), 0u);
  EXPECT_EQ(b.size(), 3u);
  b.resize(5);
  EXPECT_EQ(b[2], 3.f);
  b.resize(2);
  EXPECT_EQ(b.to_host(), (std::vector<float>{1, 2}));
  Buffer<float> c = b.copy_to(Device::CPU);
  c[0] = 9;
  EXPECT_EQ(b[0], 1.f);
  c.fill_zero();
  EXPECT_EQ(c.to_host(), (std::vector<float>{0, 0}));
  Buffer<int> empty(0);
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.data(), nullptr);
}

TEST(Device, AutoFallsBackToCpuAndRejectsUnknown) {
  if (cuda_device_count() == 0) {
    EXPECT_EQ(resolve_device("auto"), Device::CPU);
    EXPECT_THROW(resolve_device("cuda"), Error);
  }
  EXPECT_EQ(resolve_device("cpu"), Device::CPU);
  EXPECT_THROW(resolve_device("gpu"), Error);
}

TEST(ParallelFor, VisitsEveryIndexOnce) {
  for (std::size_t n : kSizes) {
    std::vector<int> hits(n, 0);
    int* h = hits.data();
    parallel_for(Device::CPU, n, [h](std::size_t i) { h[i] += 1; });
    EXPECT_TRUE(std::all_of(hits.begin(), hits.end(), [](int v) { return v == 1; })) << "n=" << n;
  }
}

TEST(SortByKey, MatchesStableSortForAllSizesAndBitWidths) {
  std::mt19937_64 rng(1);
  for (int end_bit : {64, 40, 8}) {
    const std::uint64_t mask = end_bit == 64 ? ~0ull : ((1ull << end_bit) - 1);
    for (std::size_t n : kSizes) {
      // few distinct keys in some runs so that stability is exercised
      auto keys = random_keys(n, rng, n % 2 ? mask : (mask & 0xF));
      std::vector<std::uint32_t> vals(n);
      std::iota(vals.begin(), vals.end(), 0u);
      std::vector<std::size_t> order(n);
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return keys[a] < keys[b]; });
      Buffer<std::uint64_t> kb(keys, Device::CPU);
      Buffer<std::uint32_t> vb(vals, Device::CPU);
      sort_by_key(kb, vb, end_bit);
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(kb[i], keys[order[i]]) << "n=" << n << " i=" << i;
        ASSERT_EQ(vb[i], order[i]) << "n=" << n << " i=" << i;
      }
    }
  }
}

TEST(SortByKey, RejectsMismatchedSizes) {
  Buffer<std::uint64_t> k(3);
  Buffer<std::uint32_t> v(2);
  EXPECT_THROW(sort_by_key(k, v), Error);
}

TEST(Scan, ExclusiveAndInclusiveIntegers) {
  std::mt19937 rng(2);
  for (std::size_t n : kSizes) {
    std::vector<std::uint32_t> in(n);
    for (auto& x : in) x = rng() % 100;
    std::vector<std::uint32_t> ex(n), inc(n);
    std::exclusive_scan(in.begin(), in.end(), ex.begin(), 0u);
    std::inclusive_scan(in.begin(), in.end(), inc.begin());
    Buffer<std::uint32_t> bin(in, Device::CPU), bout(n);
    exclusive_scan(bin, bout);
    EXPECT_EQ(bout.to_host(), ex) << "n=" << n;
    inclusive_scan(bin, bout);
    EXPECT_EQ(bout.to_host(), inc) << "n=" << n;
    inclusive_scan(bin, bin);  // in place
    EXPECT_EQ(bin.to_host(), inc) << "in-place n=" << n;
  }
}

TEST(Scan, FloatsAgreeWithDoubleReference) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  for (std::size_t n : kSizes) {
    std::vector<float> in(n);
    for (auto& x : in) x = u(rng);
    Buffer<float> bin(in, Device::CPU), bout(n);
    exclusive_scan(bin, bout);
    double acc = 0;
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_NEAR(bout[i], acc, 1e-4 * (1 + std::abs(acc))) << "n=" << n << " i=" << i;
      acc += in[i];
    }
  }
}

TEST(Reduce, SumAndMax) {
  std::mt19937 rng(4);
  for (std::size_t n : kSizes) {
    std::vector<std::int32_t> in(n);
    for (auto& x : in) x = int(rng() % 2001) - 1000;
    Buffer<std::int32_t> b(in, Device::CPU);
    EXPECT_EQ(reduce_sum(b), std::accumulate(in.begin(), in.end(), 0)) << "n=" << n;
    EXPECT_EQ(reduce_max(b), n ? *std::max_element(in.begin(), in.end()) : std::numeric_limits<int>::lowest());
    std::vector<double> d(in.begin(), in.end());
    Buffer<double> bd(d, Device::CPU);
    EXPECT_DOUBLE_EQ(reduce_sum(bd), std::accumulate(d.begin(), d.end(), 0.0));
  }
}
