/* The few words that differ between kernel languages and host C++, so that the files under cl/ are one
 * source for the device kernels and the sequential reference alike. Each backend's words are in its
 * folder (src/compute/opencl/dt_prelude_opencl.h, src/compute/cuda/dt_prelude_cuda.h); host C++'s are here. */
#ifndef DT_PRELUDE_H
#define DT_PRELUDE_H

/* A conversion that is a C cast in kernels and a named cast in C++ (which warns on C casts). */
#ifdef __cplusplus
#define DT_CAST(type, x) static_cast<type>(x)
#else
#define DT_CAST(type, x) ((type)(x))
#endif

/* A device program begins with its backend's words (src/compute/<name>/dt_prelude_<name>.h, which defines
 * DT_DEVICE_PRELUDE); without them, this is host C++. */
#if !defined(DT_DEVICE_PRELUDE)
#if defined(__OPENCL_VERSION__) || defined(__CUDACC_RTC__)
#error "cl/ kernel text compiled without its backend's prelude (compute::<name>::prelude_files)"
#endif
#include <cmath>
#include <cstdint>
typedef std::uint16_t dt_u16;
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
