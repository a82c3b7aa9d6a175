#include "core/compute/block_cache.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <utility>

namespace goris {

BlockCache::BlockCache(RawAlloc raw_alloc, RawFree raw_free, bool enabled)
    : raw_alloc_(std::move(raw_alloc)), raw_free_(std::move(raw_free)), enabled_(enabled) {}

std::size_t BlockCache::size_class(std::size_t bytes) {
  constexpr std::size_t kMin = 512;
  if (bytes <= kMin) return kMin;
  const int p = std::bit_width(bytes - 1);     // 2^p >= bytes > 2^(p-1)
  const std::size_t step = std::size_t(1) << (p - 4);  // 8 classes between 2^(p-1) and 2^p
  return (bytes + step - 1) / step * step;
}

void* BlockCache::allocate(std::size_t bytes) {
  const std::size_t cls = size_class(bytes);
  std::lock_guard<std::mutex> lock(mutex_);
  void* p = nullptr;
  auto it = free_.find(cls);
  if (it != free_.end() && !it->second.empty()) {
    p = it->second.back();
    it->second.pop_back();
    stats_.cached -= cls;
  } else {
    p = raw_alloc_(cls);
    if (!p && stats_.cached > 0) {  // out of memory: give the cache back and try once more
      trim_locked();
      p = raw_alloc_(cls);
    }
    if (!p) return nullptr;
    ++stats_.raw_allocs;
  }
  sizes_[p] = cls;
  stats_.in_use += cls;
  stats_.peak_in_use = std::max(stats_.peak_in_use, stats_.in_use);
  return p;
}

void BlockCache::release(void* p) {
  if (!p) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = sizes_.find(p);
  if (it == sizes_.end()) throw std::logic_error("BlockCache::release: a pointer this cache did not hand out");
  const std::size_t cls = it->second;
  sizes_.erase(it);
  stats_.in_use -= cls;
  if (enabled_) {
    free_[cls].push_back(p);
    stats_.cached += cls;
  } else {
    raw_free_(p);
  }
}

void BlockCache::trim() {
  std::lock_guard<std::mutex> lock(mutex_);
  trim_locked();
}

void BlockCache::trim_locked() {
  for (auto& [cls, blocks] : free_)
    for (void* p : blocks) raw_free_(p);
  free_.clear();
  stats_.cached = 0;
}

DeviceMemoryStats BlockCache::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace goris
