#pragma once
// Turns a failed CUDA runtime call into a goris::Error naming the call site. CUDA translation units only.
#include <cuda_runtime.h>

#include <string>

#include "core/util/error.h"

#define GORIS_CUDA_CHECK(call)                                                                          \
  do {                                                                                                  \
    cudaError_t goris_err_ = (call);                                                                    \
    if (goris_err_ != cudaSuccess)                                                                      \
      throw ::goris::Error(std::string("CUDA error in ") + #call + " (" + __FILE__ + ":" +             \
                           std::to_string(__LINE__) + "): " + cudaGetErrorString(goris_err_));          \
  } while (0)
