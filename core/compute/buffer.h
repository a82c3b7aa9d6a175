#pragma once
#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/compute/memory.h"

namespace goris {

// A typed array that lives on exactly one device. Moving is cheap, copying is explicit (copy_to /
// to_host / upload), so a host<->device transfer is always visible in the code that causes it.
template <class T>
class Buffer {
  static_assert(std::is_trivially_copyable_v<T>, "Buffer<T> holds plain data only");

 public:
  Buffer() = default;
  explicit Buffer(std::size_t n, Device d = Device::CPU) : dev_(d), n_(n) {
    ptr_ = static_cast<T*>(device_alloc(d, n * sizeof(T)));
  }
  Buffer(const std::vector<T>& host, Device d) : Buffer(host.size(), d) { upload(host.data(), host.size()); }
  ~Buffer() { device_free(dev_, ptr_); }

  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& o) noexcept : dev_(o.dev_), ptr_(std::exchange(o.ptr_, nullptr)), n_(std::exchange(o.n_, 0)) {}
  Buffer& operator=(Buffer&& o) noexcept {
    if (this != &o) {
      device_free(dev_, ptr_);
      dev_ = o.dev_;
      ptr_ = std::exchange(o.ptr_, nullptr);
      n_ = std::exchange(o.n_, 0);
    }
    return *this;
  }

  T* data() { return ptr_; }
  const T* data() const { return ptr_; }
  std::size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  Device device() const { return dev_; }
  std::size_t bytes() const { return n_ * sizeof(T); }

  // Host-side element access; only valid for CPU buffers.
  T& operator[](std::size_t i) { return ptr_[i]; }
  const T& operator[](std::size_t i) const { return ptr_[i]; }

  void upload(const T* host, std::size_t n) { device_copy(ptr_, dev_, host, Device::CPU, std::min(n, n_) * sizeof(T)); }
  void download(T* host) const { device_copy(host, Device::CPU, ptr_, dev_, bytes()); }
  std::vector<T> to_host() const {
    std::vector<T> v(n_);
    download(v.data());
    return v;
  }
  Buffer copy_to(Device d) const {
    Buffer b(n_, d);
    device_copy(b.ptr_, d, ptr_, dev_, bytes());
    return b;
  }
  void fill_zero() { device_memset_zero(dev_, ptr_, bytes()); }

  // Changes the size, keeping the first min(old, new) elements.
  void resize(std::size_t n) {
    if (n == n_) return;
    Buffer b(n, dev_);
    device_copy(b.ptr_, dev_, ptr_, dev_, std::min(n, n_) * sizeof(T));
    *this = std::move(b);
  }

 private:
  Device dev_ = Device::CPU;
  T* ptr_ = nullptr;
  std::size_t n_ = 0;
};

}  // namespace goris
