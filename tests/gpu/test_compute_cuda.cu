// CUDA compute primitives against the CPU ones on the same random inputs. Skips without a GPU.
#include <random>
#include <vector>

#include "core/compute/buffer.h"
#include "core/compute/ordered_sum.h"
#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "tests/support/test_support.h"

using namespace goris;

namespace {
const std::vector<std::size_t> kSizes = {0, 1, 2, 3, 7, 255, 256, 257, 1000, 4097, 65537, 300001};

// nvcc does not allow extended __device__ lambdas inside a gtest TestBody (a private member function).
void fill_on_cuda(Buffer<std::uint32_t>& b) {
  std::uint32_t* p = b.data();
  parallel_for(Device::CUDA, b.size(), [p] __device__(std::size_t i) { p[i] = std::uint32_t(i * 3 + 1); });
}
}  // namespace

TEST(CudaCompute, ParallelForWritesEveryIndex) {
  GORIS_REQUIRE_GPU();
  for (std::size_t n : kSizes) {
    Buffer<std::uint32_t> b(n, Device::CUDA);
    fill_on_cuda(b);
    auto h = b.to_host();
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(h[i], i * 3 + 1);
  }
}

TEST(CudaCompute, SortByKeyMatchesCpuExactly) {
  GORIS_REQUIRE_GPU();
  std::mt19937_64 rng(5);
  for (int end_bit : {64, 40}) {
    for (std::size_t n : kSizes) {
      std::vector<std::uint64_t> keys(n);
      for (auto& k : keys) k = rng() & (n % 2 ? (end_bit == 64 ? ~0ull : (1ull << end_bit) - 1) : 0xFull);
      std::vector<std::uint32_t> vals(n);
      for (std::size_t i = 0; i < n; ++i) vals[i] = std::uint32_t(i);
      Buffer<std::uint64_t> kc(keys, Device::CPU), kg(keys, Device::CUDA);
      Buffer<std::uint32_t> vc(vals, Device::CPU), vg(vals, Device::CUDA);
      sort_by_key(kc, vc, end_bit);
      sort_by_key(kg, vg, end_bit);
      ASSERT_EQ(kg.to_host(), kc.to_host()) << "n=" << n;
      ASSERT_EQ(vg.to_host(), vc.to_host()) << "n=" << n;
    }
  }
}

TEST(CudaCompute, ScansAndReductionsMatchCpu) {
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(-1, 1);
  for (std::size_t n : kSizes) {
    std::vector<std::uint32_t> iv(n);
    std::vector<float> fv(n);
    for (std::size_t i = 0; i < n; ++i) {
      iv[i] = rng() % 1000;
      fv[i] = u(rng);
    }
    Buffer<std::uint32_t> ic(iv, Device::CPU), ig(iv, Device::CUDA), oc(n), og(n, Device::CUDA);
    exclusive_scan(ic, oc);
    exclusive_scan(ig, og);
    ASSERT_EQ(og.to_host(), oc.to_host()) << "n=" << n;
    inclusive_scan(ig, og);
    inclusive_scan(ic, oc);
    ASSERT_EQ(og.to_host(), oc.to_host()) << "n=" << n;
    EXPECT_EQ(reduce_sum(ig), reduce_sum(ic));
    EXPECT_EQ(reduce_max(ig), reduce_max(ic));

    Buffer<float> fc(fv, Device::CPU), fg(fv, Device::CUDA), fo(n), fgo(n, Device::CUDA);
    inclusive_scan(fc, fo);
    inclusive_scan(fg, fgo);
    auto a = fo.to_host(), b = fgo.to_host();
    for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(a[i], b[i], 1e-3 * (1 + std::abs(a[i]))) << "n=" << n;
    EXPECT_NEAR(reduce_sum(fg), reduce_sum(fc), 1e-3 * (1 + std::abs(reduce_sum(fc))));
    EXPECT_EQ(reduce_max(fg), reduce_max(fc));
  }
}

// Ordered sums are plain float adds in key order: CUDA and CPU give the same bits.
TEST(CudaCompute, OrderedSumsMatchCpuExactly) {
  GORIS_REQUIRE_GPU();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1e3f, 1e3f);
  const std::uint32_t targets = 1000;
  const int width = 3;
  for (std::size_t n : kSizes) {
    const OrderedKeyLayout layout(targets, n);
    std::vector<std::uint64_t> keys(n);
    std::vector<float> rows(n * width), out(targets * width, 0.5f);
    for (std::size_t i = 0; i < n; ++i) keys[i] = i % 5 == 4 ? layout.unused() : layout.key(rng() % targets, n - 1 - i);
    for (float& v : rows) v = u(rng);
    Buffer<std::uint64_t> kc(keys, Device::CPU), kg(keys, Device::CUDA);
    Buffer<float> rg(rows, Device::CUDA), oc(out, Device::CPU), og(out, Device::CUDA);
    add_rows_in_key_order(layout, kc, rows.data(), width, oc.data());
    add_rows_in_key_order(layout, kg, rg.data(), width, og.data());
    ASSERT_EQ(og.to_host(), oc.to_host()) << "n=" << n;
  }
}
