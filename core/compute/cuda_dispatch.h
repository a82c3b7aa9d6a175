#pragma once
// GORIS_CUDA_CALL(module, call): how code that runs on either device calls a CUDA driver (a function
// defined in a .cu file, declared in its X_cuda.h). With the CUDA backend the macro is the call. A build
// without nvcc has no definitions of those drivers, so there the macro throws goris::Error naming `module`
// ("rasterizer: CUDA device requested but this build has no CUDA backend") instead. The call still sits in
// an unevaluated decltype there: it is type-checked against its declaration but never emitted, so that
// build needs no definitions of the drivers. The macro has the call's type, so `return GORIS_CUDA_CALL(...)`
// also works for drivers that return a value.
#include "core/util/error.h"

namespace goris::detail {

// What GORIS_CUDA_CALL is in a build without the CUDA backend; R is the type of the call it replaces.
template <class R>
[[noreturn]] R no_cuda_backend(const char* module) {
  throw Error(module, "CUDA device requested but this build has no CUDA backend");
}

}  // namespace goris::detail

#ifdef GORIS_WITH_CUDA
#define GORIS_CUDA_CALL(module, ...) (__VA_ARGS__)
#else
#define GORIS_CUDA_CALL(module, ...) (::goris::detail::no_cuda_backend<decltype(__VA_ARGS__)>(module))
#endif
