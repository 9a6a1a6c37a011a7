/* OpenCL C's words in CUDA's terms, for the kernels under cl/ (cl/dt_prelude.h holds host C++'s and the
 * shared ones). The CUDA backend puts this text before every program NVRTC compiles (cuda_program.cpp), so
 * cl/ names no backend; DT_DEVICE_PRELUDE tells cl/dt_prelude.h that a device's words are here. */
#define DT_DEVICE_PRELUDE 1
typedef unsigned int uint;
typedef unsigned long long ulong;
typedef unsigned short dt_u16;
typedef unsigned int dt_u32;
typedef unsigned long long dt_u64;
#define DT_FN __device__ __host__ inline
#define DT_DEVICE_FN __device__ inline
#define DT_LOCAL_PTR /* CUDA pointers into shared memory are generic */
#define __kernel extern "C" __global__
#define __global
#define __local __shared__
#define restrict __restrict__
/* A kernel's __launch_bounds__ where its program asks for DT_RESIDENT_GROUPS groups on each multiprocessor
 * (render_weigh, rasterize: compute/resident_groups.hpp): NVRTC then keeps the registers within that share. */
#if defined(DT_RESIDENT_GROUPS) && DT_RESIDENT_GROUPS > 0
#define DT_RESIDENCY __launch_bounds__(DT_GROUP_SIZE, DT_RESIDENT_GROUPS)
#else
#define DT_RESIDENCY
#endif
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
/* a * b + c rounded once: NVRTC contracts a plain product and sum into an FMA or not as each call site
 * compiles, so two kernels drawing the same triangle could round its depth differently (cl/rasterize.cl) */
#define dt_mul_add(a, b, c) fmaf((a), (b), (c))
#define dt_as_uint __float_as_uint
#define dt_as_float __uint_as_float
#define dt_atomic_min_u32(p, v) atomicMin((p), (v))
#define dt_atomic_min_u64(p, v) atomicMin((p), (v)) /* unsigned long long, sm_35 on */
#define dt_atomic_add_u32(p, v) atomicAdd((p), (v))
#define dt_atomic_add_local_u32(p, v) atomicAdd((p), (v))
