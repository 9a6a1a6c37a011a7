/* The per-pixel-time occlusion's frame indices (dt_time_index.h): their start, their retirement before
 * an index comes round again, and the resampling's gather of their rows where the row length is odd
 * (even rows go through gather_pixels as 32-bit words). Part of resample.cl's program (it includes
 * this file at its end: dt_resampling). DT_GROUP_SIZE: work-items per group. */
#include "dt_time_index.h"

/* A work-group per particle: every pixel's index to value. */
__kernel void fill_time_indices(__global dt_u16* indices, uint pixels, uint value) {
  __global dt_u16* row = indices + DT_CAST(ulong, get_group_id(0)) * pixels;
  for (uint k = get_local_id(0); k < pixels; k += DT_GROUP_SIZE) row[k] = DT_CAST(dt_u16, value);
}

/* Every index last written DT_TIME_RETIRE_AGE frames before now_index or longer becomes DT_TIME_NEVER;
 * the grid strides over all count indices. */
__kernel void retire_time_indices(__global dt_u16* indices, ulong count, uint now_index) {
  for (ulong i = get_global_id(0); i < count; i += get_global_size(0)) {
    const uint index = indices[i];
    if (index == DT_TIME_NEVER) continue;
    const uint age = (now_index + DT_TIME_CYCLE - index) % DT_TIME_CYCLE;
    if (age >= DT_TIME_RETIRE_AGE) indices[i] = DT_CAST(dt_u16, DT_TIME_NEVER);
  }
}

/* Children copy their parent's row of indices, a work-group per child (rows of odd length). */
__kernel void gather_time_indices(__global const dt_u16* from, __global dt_u16* to, __global const uint* parents,
                                  uint pixels, __global const float* estimate) {
  if (!dt_resampling(estimate)) return;
  const uint child = get_group_id(0);
  __global const dt_u16* source = from + DT_CAST(ulong, parents[child]) * pixels;
  __global dt_u16* target = to + DT_CAST(ulong, child) * pixels;
  for (uint k = get_local_id(0); k < pixels; k += DT_GROUP_SIZE) target[k] = source[k];
}
