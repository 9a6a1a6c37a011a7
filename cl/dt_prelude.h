/* The few words that differ between OpenCL C, CUDA and host C++, so that the files under cl/ are
 * one source for the device kernels and the sequential reference alike. */
#ifndef DT_PRELUDE_H
#define DT_PRELUDE_H

/* A conversion that is a C cast in kernels and a named cast in C++ (which warns on C casts). */
#ifdef __cplusplus
#define DT_CAST(type, x) static_cast<type>(x)
#else
#define DT_CAST(type, x) ((type)(x))
#endif

#if defined(__OPENCL_VERSION__)
typedef uint dt_u32;
typedef ulong dt_u64;
#define DT_FN inline
#define DT_DEVICE_FN inline
#define DT_LOCAL_PTR __local /* a pointer parameter into work-group memory */
#define dt_mulhi(a, b) mul_hi(DT_CAST(dt_u32, a), DT_CAST(dt_u32, b))
#define dt_logf log
#define dt_sqrtf sqrt
#define dt_cospif cospi
#define dt_sinpif sinpi
#define dt_divide(a, b) ((a) / (b))                  /* float division to OpenCL's default 2.5 ulp */
#define dt_as_uint as_uint                           /* a float's bits */
#define dt_as_float as_float                         /* the float of some bits */
#define dt_atomic_min_u32(p, v) atomic_min((p), (v)) /* 32-bit uint, global or local memory */
#elif defined(__CUDACC__) || defined(__CUDACC_RTC__)
/* CUDA (NVRTC compiles the same text): OpenCL C's words in CUDA's terms. */
typedef unsigned int uint;
typedef unsigned long long ulong;
typedef unsigned int dt_u32;
typedef unsigned long long dt_u64;
#define DT_FN __device__ __host__ inline
#define DT_DEVICE_FN __device__ inline
#define DT_LOCAL_PTR /* CUDA pointers into shared memory are generic */
#define __kernel extern "C" __global__
#define __global
#define __local __shared__
#define restrict __restrict__
#define CLK_LOCAL_MEM_FENCE 1
#define CLK_GLOBAL_MEM_FENCE 2
#define barrier(flags) __syncthreads()
__device__ inline uint dt_dim3(uint3 v, uint d) {
  return d == 0 ? v.x : (d == 1 ? v.y : v.z);
}
__device__ inline uint dt_dim3(dim3 v, uint d) {
  return d == 0 ? v.x : (d == 1 ? v.y : v.z);
}
#define get_local_id(d) dt_dim3(threadIdx, (d))
#define get_group_id(d) dt_dim3(blockIdx, (d))
#define get_local_size(d) dt_dim3(blockDim, (d))
#define get_num_groups(d) dt_dim3(gridDim, (d))
#define get_global_id(d) (get_group_id(d) * get_local_size(d) + get_local_id(d))
#define get_global_size(d) (get_num_groups(d) * get_local_size(d))
#define dt_mulhi(a, b) __umulhi(DT_CAST(dt_u32, a), DT_CAST(dt_u32, b))
#define dt_logf logf
#define dt_sqrtf sqrtf
#define dt_cospif cospif
#define dt_sinpif sinpif
#define dt_divide(a, b) __fdividef((a), (b)) /* 2 ulp; CUDA's `/` rounds correctly, and slowly */
#define dt_as_uint __float_as_uint
#define dt_as_float __uint_as_float
#define dt_atomic_min_u32(p, v) atomicMin((p), (v))
#else /* host C++ */
#include <cmath>
#include <cstdint>
typedef std::uint32_t dt_u32;
typedef std::uint64_t dt_u64;
#define DT_FN inline
inline dt_u32 dt_mulhi(dt_u32 a, dt_u32 b) {
  return static_cast<dt_u32>((static_cast<dt_u64>(a) * b) >> 32);
}
inline float dt_logf(float x) {
  return std::log(x);
}
inline float dt_sqrtf(float x) {
  return std::sqrt(x);
}
inline float dt_cospif(float x) {
  return static_cast<float>(std::cos(3.14159265358979323846 * static_cast<double>(x)));
}
inline float dt_sinpif(float x) {
  return static_cast<float>(std::sin(3.14159265358979323846 * static_cast<double>(x)));
}
#endif

/* Below every finite float: the start of a maximum search (INFINITY is not defined under NVRTC). */
#define DT_LOWEST (-3.402823466e+38f)

#endif
