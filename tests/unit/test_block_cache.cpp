// The caching allocator behind CUDA buffers (core/compute/block_cache.h), on a fake device whose memory is
// plain host memory with a capacity: reuse per size class, the statistics, giving the cache back when the
// device runs out, and the uncached mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>

#include "core/compute/block_cache.h"

using namespace goris;

namespace {

// Host memory standing in for a device of `capacity` bytes.
struct FakeDevice {
  std::size_t capacity, used = 0, allocs = 0, frees = 0;
  std::set<void*> live;
  std::map<void*, std::size_t> sizes;
  explicit FakeDevice(std::size_t cap) : capacity(cap) {}
  BlockCache cache(bool enabled = true) {
    return BlockCache(
        [this](std::size_t n) -> void* {
          if (used + n > capacity) return nullptr;
          used += n;
          ++allocs;
          void* p = std::malloc(n);
          live.insert(p);
          sizes[p] = n;
          return p;
        },
        [this](void* p) {
          used -= sizes.at(p);
          ++frees;
          live.erase(p);
          std::free(p);
        },
        enabled);
  }
};

}  // namespace

TEST(BlockCache, SizeClassesWasteAtMostAnEighth) {
  EXPECT_EQ(BlockCache::size_class(1), 512u);
  EXPECT_EQ(BlockCache::size_class(512), 512u);
  EXPECT_EQ(BlockCache::size_class(513), 576u);
  EXPECT_EQ(BlockCache::size_class(1024), 1024u);
  EXPECT_EQ(BlockCache::size_class(1025), 1152u);
  for (std::size_t n = 1; n < (std::size_t(1) << 26); n = n * 3 / 2 + 7) {
    const std::size_t c = BlockCache::size_class(n);
    ASSERT_GE(c, n);
    ASSERT_LE(double(c), std::max(512.0, 1.125 * double(n))) << n;
    ASSERT_EQ(BlockCache::size_class(c), c) << "a class is its own class";
  }
}

TEST(BlockCache, FreedBlocksAreReusedAndCountedApartFromTheCache) {
  FakeDevice dev(1 << 20);
  BlockCache cache = dev.cache();
  void* a = cache.allocate(1000);
  void* b = cache.allocate(5000);
  EXPECT_EQ(dev.allocs, 2u);
  EXPECT_EQ(cache.stats().in_use, BlockCache::size_class(1000) + BlockCache::size_class(5000));
  cache.release(a);
  EXPECT_EQ(cache.stats().cached, BlockCache::size_class(1000));
  EXPECT_EQ(dev.frees, 0u);
  void* c = cache.allocate(990);  // the same class: the cached block comes back
  EXPECT_EQ(c, a);
  EXPECT_EQ(dev.allocs, 2u);
  EXPECT_EQ(cache.stats().cached, 0u);
  void* d = cache.allocate(100000);  // another class: a new block
  EXPECT_EQ(dev.allocs, 3u);
  const DeviceMemoryStats peak = cache.stats();
  cache.release(b);
  cache.release(c);
  cache.release(d);
  const DeviceMemoryStats s = cache.stats();
  EXPECT_EQ(s.in_use, 0u);
  EXPECT_EQ(s.peak_in_use, peak.in_use);
  EXPECT_EQ(s.cached, dev.used);
  EXPECT_EQ(s.raw_allocs, 3u);
  cache.trim();
  EXPECT_EQ(dev.used, 0u);
  EXPECT_EQ(cache.stats().cached, 0u);
  EXPECT_THROW(cache.release(reinterpret_cast<void*>(16)), std::logic_error);
  cache.release(nullptr);
}

TEST(BlockCache, RunningOutGivesTheCacheBackAndRetries) {
  FakeDevice dev(64 * 1024);
  BlockCache cache = dev.cache();
  void* small = cache.allocate(40 * 1024);
  cache.release(small);  // cached: the device is still 40 KiB full
  void* big = cache.allocate(50 * 1024);
  ASSERT_NE(big, nullptr) << "the cached block should have been freed to make room";
  EXPECT_EQ(cache.stats().cached, 0u);
  EXPECT_EQ(cache.allocate(30 * 1024), nullptr) << "nothing cached to give back: out of memory";
  cache.release(big);
}

TEST(BlockCache, UncachedModeFreesAtOnce) {
  FakeDevice dev(1 << 20);
  BlockCache cache = dev.cache(false);
  void* a = cache.allocate(3000);
  cache.release(a);
  EXPECT_EQ(dev.frees, 1u);
  EXPECT_EQ(dev.used, 0u);
  EXPECT_EQ(cache.stats().cached, 0u);
  EXPECT_EQ(cache.stats().peak_in_use, BlockCache::size_class(3000));
}
