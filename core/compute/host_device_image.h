#pragma once
// Images that cross between the host and the device a stage runs on, without a copy on the CPU: the
// trainer reads rendered images on the host and hands host gradients to the backward passes.
#include <cstddef>
#include <vector>

#include "core/compute/buffer.h"
#include "core/compute/device.h"
#include "core/compute/memory.h"

namespace goris {

// A device image readable on the host: the image itself on the CPU, a downloaded copy otherwise.
class HostView {
 public:
  HostView(const float* p, std::size_t n, Device d) {
    if (d == Device::CPU) {
      ptr_ = p;
    } else {
      copy_.resize(n);
      device_copy(copy_.data(), Device::CPU, p, d, n * sizeof(float));
      ptr_ = copy_.data();
    }
  }
  const float* data() const { return ptr_; }

 private:
  std::vector<float> copy_;
  const float* ptr_ = nullptr;
};

// A host gradient image as the rasterizer's backward pass reads it (uploaded for a CUDA forward pass).
class DeviceGrad {
 public:
  DeviceGrad(const std::vector<float>& host, Device d) {
    if (d == Device::CPU) {
      ptr_ = host.data();
    } else {
      buf_ = Buffer<float>(host, d);
      ptr_ = buf_.data();
    }
  }
  const float* data() const { return ptr_; }

 private:
  Buffer<float> buf_;
  const float* ptr_ = nullptr;
};

}  // namespace goris
