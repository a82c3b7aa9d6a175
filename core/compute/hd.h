#pragma once
// GORIS_HD marks functions whose maths is shared by the CPU and CUDA backends: it expands to
// __host__ __device__ under nvcc and to nothing for the host compiler. Write kernel maths once with it.
#if defined(__CUDACC__)
#define GORIS_HD __host__ __device__
#define GORIS_DEVICE_CODE 1
#else
#define GORIS_HD
#endif
#define GORIS_HDI GORIS_HD inline

// Device-generic drivers that take the device at run time (parallel_for and the ops headers built on it)
// compile differently under nvcc (.cu: launches kernels) and the host compiler (.cpp: throws for CUDA).
// The linker keeps one copy of each inline or template function, so if both translation-unit kinds
// instantiated e.g. make_rays<float> under one name, a CUDA call could land in the host copy. Wrapping such
// headers in GORIS_BACKEND_NAMESPACE_BEGIN/END gives each compiler its own inline namespace, hence its own
// symbols (tests/build/check_backend_symbols.sh checks the objects for shared ones).
#if defined(__CUDACC__)
#define GORIS_BACKEND_NAMESPACE_BEGIN inline namespace backend_nvcc {
#else
#define GORIS_BACKEND_NAMESPACE_BEGIN inline namespace backend_host {
#endif
#define GORIS_BACKEND_NAMESPACE_END }
