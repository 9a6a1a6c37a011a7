/* The per-pixel-time occlusion's frame indices (dt_time_index.h): their start and their retirement
 * before an index comes round again (the resampling's gather of their rows is weigh's: weigh.cl).
 * Part of resample.cl's program (it includes this file at its end). DT_GROUP_SIZE: work-items per group. */
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
