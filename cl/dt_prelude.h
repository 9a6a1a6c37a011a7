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
#define dt_mulhi(a, b) mul_hi(DT_CAST(dt_u32, a), DT_CAST(dt_u32, b))
#define dt_logf log
#define dt_sqrtf sqrt
#define dt_cospif cospi
#define dt_sinpif sinpi
#elif defined(__CUDACC__)
typedef unsigned int dt_u32;
typedef unsigned long long dt_u64;
#define DT_FN __device__ __host__ inline
#define dt_mulhi(a, b) __umulhi(DT_CAST(dt_u32, a), DT_CAST(dt_u32, b))
#define dt_logf logf
#define dt_sqrtf sqrtf
#define dt_cospif cospif
#define dt_sinpif sinpif
#else /* host C++ */
#include <cmath>
#include <cstdint>
typedef std::uint32_t dt_u32;
typedef std::uint64_t dt_u64;
#define DT_FN inline
inline dt_u32 dt_mulhi(dt_u32 a, dt_u32 b) { return static_cast<dt_u32>((static_cast<dt_u64>(a) * b) >> 32); }
inline float dt_logf(float x) { return std::log(x); }
inline float dt_sqrtf(float x) { return std::sqrt(x); }
inline float dt_cospif(float x) { return static_cast<float>(std::cos(3.14159265358979323846 * static_cast<double>(x))); }
inline float dt_sinpif(float x) { return static_cast<float>(std::sin(3.14159265358979323846 * static_cast<double>(x))); }
#endif

#endif
