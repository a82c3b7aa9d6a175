// kernel_profile: per-launch-site timing of parallel_for and of Scope blocks (CPU here; the CUDA path records
// the same way).
#include <gtest/gtest.h>

#include <vector>

#include "core/compute/kernel_profile.h"
#include "core/compute/parallel_for.h"

using namespace goris;

namespace {

void fill_twice(std::vector<float>& v) {
  float* p = v.data();
  parallel_for(Device::CPU, v.size(), [=](std::size_t i) { p[i] = 1.0f; });
  parallel_for(Device::CPU, v.size(), [=](std::size_t i) { p[i] += 1.0f; });
}

template <class T>
void scale(std::vector<T>& v, T s) {
  T* p = v.data();
  parallel_for(Device::CPU, v.size(), [=](std::size_t i) { p[i] *= s; });
}

}  // namespace

TEST(KernelProfile, RecordsEachCallSiteOnlyWhenEnabled) {
  std::vector<float> v(1000);
  kernel_profile::reset();
  fill_twice(v);  // disabled: nothing recorded
  EXPECT_TRUE(kernel_profile::sites().empty());

  kernel_profile::enable(true);
  fill_twice(v);
  fill_twice(v);
  scale(v, 0.5f);
  kernel_profile::enable(false);
  scale(v, 2.0f);  // disabled again
  EXPECT_FLOAT_EQ(v[0], 2.0f);

  const auto sites = kernel_profile::sites();
  ASSERT_EQ(sites.size(), 3u);  // two lines in fill_twice, one in scale
  long fill_calls = 0, scale_calls = 0;
  for (const auto& s : sites) {
    EXPECT_GE(s.ms, 0.0);
    EXPECT_NE(s.where.find("test_kernel_profile.cpp:"), std::string::npos) << s.where;
    if (s.function.find("fill_twice") != std::string::npos) fill_calls += s.calls;
    if (s.function.find("scale") != std::string::npos) {
      scale_calls += s.calls;
      EXPECT_NE(s.function.find("<float>"), std::string::npos) << s.function;  // the template argument is named
    }
  }
  EXPECT_EQ(fill_calls, 4);
  EXPECT_EQ(scale_calls, 1);
  for (std::size_t i = 1; i < sites.size(); ++i) EXPECT_GE(sites[i - 1].ms, sites[i].ms);  // largest first

  const std::string table = kernel_profile::markdown_table();
  EXPECT_NE(table.find("5 launches (parallel_for and timed blocks) at 3 sites"), std::string::npos) << table;
  EXPECT_NE(table.find("| launch site | where | calls |"), std::string::npos);
  kernel_profile::reset();
  EXPECT_TRUE(kernel_profile::sites().empty());
}

TEST(KernelProfile, ScopeTimesABlockUnderItsSite) {
  kernel_profile::reset();
  { kernel_profile::Scope off(Device::CPU); }  // disabled: nothing recorded
  EXPECT_TRUE(kernel_profile::sites().empty());
  kernel_profile::enable(true);
  for (int i = 0; i < 3; ++i) {
    kernel_profile::Scope scope(Device::CPU);
    std::vector<float> v(100000, 1.0f);
    volatile float sum = 0;
    for (float x : v) sum = sum + x;
  }
  kernel_profile::enable(false);
  const auto sites = kernel_profile::sites();
  ASSERT_EQ(sites.size(), 1u);
  EXPECT_EQ(sites[0].calls, 3);
  EXPECT_GT(sites[0].ms, 0.0);
  EXPECT_NE(sites[0].function.find("ScopeTimesABlockUnderItsSite"), std::string::npos) << sites[0].function;
  kernel_profile::reset();
}
