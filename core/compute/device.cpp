#include "core/compute/device.h"

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

Device resolve_device(const std::string& choice) {
  if (choice == "cpu") return Device::CPU;
  if (choice == "auto") return cuda_device_count() > 0 ? Device::CUDA : Device::CPU;
  if (choice == "cuda") {
    if (cuda_device_count() > 0) return Device::CUDA;
    throw Error("--device cuda: no usable CUDA device (" + cuda_device_description() + ")");
  }
  throw Error("--device: unknown value '" + choice + "' (expected auto, cpu or cuda)");
}

}  // namespace goris
