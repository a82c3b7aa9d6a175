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
