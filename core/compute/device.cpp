#include "core/compute/device.h"

#include "core/compute/device_choice.h"
#include "core/util/error.h"

namespace goris {

#ifdef GORIS_WITH_CUDA
int cuda_device_count_impl();            // device_cuda.cu
std::string cuda_device_description_impl();
#endif

const char* device_name(Device d) { return d == Device::CPU ? "cpu" : "cuda"; }

bool cuda_compiled() {
#ifdef GORIS_WITH_CUDA
  return true;
#else
  return false;
#endif
}

int cuda_device_count() {
#ifdef GORIS_WITH_CUDA
  return cuda_device_count_impl();
#else
  return 0;
#endif
}

std::string cuda_device_description() {
#ifdef GORIS_WITH_CUDA
  return cuda_device_description_impl();
#else
  return "this build has no CUDA backend (nvcc was not found at configure time)";
#endif
}

Device resolve_device(DeviceChoice choice) {
  switch (choice) {
    case DeviceChoice::CPU: return Device::CPU;
    case DeviceChoice::Auto: return cuda_device_count() > 0 ? Device::CUDA : Device::CPU;
    case DeviceChoice::CUDA:
      if (cuda_device_count() > 0) return Device::CUDA;
      throw Error("--device cuda: no usable CUDA device (" + cuda_device_description() + ")");
  }
  throw Error("--device: invalid choice");
}

Device resolve_device(const std::string& choice) {
  if (const auto c = enum_from_name<DeviceChoice>(choice)) return resolve_device(*c);
  throw Error("--device: unknown value '" + choice + "' (expected " + enum_choices<DeviceChoice>() + ")");
}

}  // namespace goris
