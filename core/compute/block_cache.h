#pragma once
// A caching allocator for device memory. Training allocates and frees the same scratch buffers every
// iteration; with cudaMalloc / cudaFree each time that costs tens of microseconds per call, and cudaFree
// waits for the whole device. Freed blocks go to a free list per size class instead and the next request
// of that class reuses one. Safe because every kernel and copy runs on the one (legacy default) stream:
// work queued on a block before it was freed runs before work queued after it was handed out again.
//
// Sizes are rounded up to 8 classes per power of two (at most 12.5 % waste, 512 bytes at least). When the
// raw allocator fails, every cached block is released and the request retried once. The statistics count
// blocks handed out (in use, and its peak) apart from blocks kept in the cache, so the peak is what the
// program needed, not what the cache happened to hold.
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace goris {

struct DeviceMemoryStats {
  std::size_t in_use = 0;       // bytes of the blocks handed out (rounded sizes)
  std::size_t peak_in_use = 0;  // the largest in_use so far
  std::size_t cached = 0;       // bytes of the free blocks kept for reuse
  std::size_t raw_allocs = 0;   // calls of the raw allocator that succeeded
};

class BlockCache {
 public:
  // raw_alloc returns null when the device is out of memory (and throws for other failures).
  using RawAlloc = std::function<void*(std::size_t)>;
  using RawFree = std::function<void(void*)>;
  BlockCache(RawAlloc raw_alloc, RawFree raw_free, bool enabled = true);

  // A block of at least `bytes` (> 0), or null when the device cannot provide it even after the cache
  // was released.
  void* allocate(std::size_t bytes);
  // p must come from allocate() (null is ignored); throws std::logic_error for unknown pointers.
  void release(void* p);
  // Frees every cached block (their memory goes back to the device).
  void trim();
  DeviceMemoryStats stats() const;

  static std::size_t size_class(std::size_t bytes);

 private:
  void trim_locked();

  RawAlloc raw_alloc_;
  RawFree raw_free_;
  bool enabled_;
  mutable std::mutex mutex_;
  std::map<std::size_t, std::vector<void*>> free_;  // size class -> cached blocks
  std::unordered_map<void*, std::size_t> sizes_;    // every block handed out -> its size class
  DeviceMemoryStats stats_;
};

}  // namespace goris
