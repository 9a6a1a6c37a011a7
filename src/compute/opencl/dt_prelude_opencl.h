/* OpenCL C's words for the kernels under cl/ (cl/dt_prelude.h holds host C++'s and the shared ones). The
 * OpenCL backend puts this text before every program it builds (opencl_prelude.cpp), so cl/ names no
 * backend; DT_DEVICE_PRELUDE tells cl/dt_prelude.h that a device's words are here. */
#define DT_DEVICE_PRELUDE 1
typedef ushort dt_u16;
typedef uint dt_u32;
typedef ulong dt_u64;
#define DT_FN inline
#define DT_DEVICE_FN inline
#define DT_LOCAL_PTR __local /* a pointer parameter into work-group memory */
#define DT_RESIDENCY          /* CUDA's __launch_bounds__ (DT_RESIDENT_GROUPS); OpenCL's compilers choose */
#define dt_mulhi(a, b) mul_hi(DT_CAST(dt_u32, a), DT_CAST(dt_u32, b))
#define dt_logf log
#define dt_sqrtf sqrt
#define dt_cospif cospi
#define dt_sinpif sinpi
#define dt_divide(a, b) ((a) / (b))                  /* float division to OpenCL's default 2.5 ulp */
#define dt_mul_add(a, b, c) ((a) * (b) + (c))        /* as written (CUDA's fuses: dt_prelude_cuda.h) */
#define dt_as_uint as_uint                           /* a float's bits */
#define dt_as_float as_float                         /* the float of some bits */
#define dt_atomic_min_u32(p, v) atomic_min((p), (v)) /* 32-bit uint, global or local memory */
/* cl_khr_int64_extended_atomics: a program using it enables the extension (cl/refine_spread.cl) */
#define dt_atomic_min_u64(p, v) atom_min((volatile __global ulong*)(p), (v))
#define dt_atomic_add_u32(p, v) atomic_add((volatile __global uint*)(p), (v))
#define dt_atomic_add_local_u32(p, v) atomic_add((volatile __local uint*)(p), (v))
