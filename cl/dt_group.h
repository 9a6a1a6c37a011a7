/* Work-group reductions over DT_GROUP_SIZE work-items (a power of two, set with -D). */
#ifndef DT_GROUP_H
#define DT_GROUP_H
#include "dt_prelude.h"

/* Sum of value over the group, returned to every work-item. */
DT_DEVICE_FN float dt_group_sum(DT_LOCAL_PTR float* scratch, float value) {
  const uint lid = get_local_id(0);
  barrier(CLK_LOCAL_MEM_FENCE); /* the previous use of scratch is over */
  scratch[lid] = value;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint stride = DT_GROUP_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride) scratch[lid] += scratch[lid + stride];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  return scratch[0];
}

/* Largest of value over the group, returned to every work-item. */
DT_DEVICE_FN float dt_group_max(DT_LOCAL_PTR float* scratch, float value) {
  const uint lid = get_local_id(0);
  barrier(CLK_LOCAL_MEM_FENCE); /* the previous use of scratch is over */
  scratch[lid] = value;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint stride = DT_GROUP_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride) scratch[lid] = fmax(scratch[lid], scratch[lid + stride]);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  return scratch[0];
}

/* The group's sums of n values a work-item (acc[0 .. n), n <= 32), left in sums[0 .. n) for every
 * work-item, in a fixed order (the same sums every time). A tree per value costs a barrier per level
 * and value (12 values at 512 work-items: 120 barriers), and a tree of all n values keeps each
 * work-item adding all of them level after level; here each work-item adds 32 work-items' values of one
 * sum, then n work-items add those partials: three barriers. Each work-item's row is odd in length, so
 * that 32 work-items writing their rows, or reading one position of 32 rows, touch 32 banks. sums holds
 * DT_GROUP_SUMS_SCRATCH(n) floats. */
#define DT_GROUP_SUMS_ROW(n) ((n) | 1)
#define DT_GROUP_SUMS_LANES 32
#define DT_GROUP_SUMS_SCRATCH(n) (DT_GROUP_SIZE * DT_GROUP_SUMS_ROW(n) + DT_GROUP_SIZE)
#if DT_GROUP_SIZE % DT_GROUP_SUMS_LANES != 0
#error "dt_group_sums needs DT_GROUP_SIZE a multiple of 32"
#endif
DT_DEVICE_FN void dt_group_sums(const float* acc, uint n, DT_LOCAL_PTR float* sums) {
  const uint lid = get_local_id(0), row = DT_GROUP_SUMS_ROW(n);
  DT_LOCAL_PTR float* parts = sums + DT_GROUP_SIZE * row; /* (DT_GROUP_SIZE / 32) x 32 partials */
  /* The previous sums have been read. */
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint k = 0; k < n; ++k) sums[lid * row + k] = acc[k];
  barrier(CLK_LOCAL_MEM_FENCE);
  /* Work-item lid adds value k = lid % 32 of work-items part * 32 .. part * 32 + 31, part = lid / 32. */
  const uint k = lid % DT_GROUP_SUMS_LANES, part = lid / DT_GROUP_SUMS_LANES;
  if (k < n) {
    float total = 0.0f;
    for (uint lane = 0; lane < DT_GROUP_SUMS_LANES; ++lane)
      total += sums[(part * DT_GROUP_SUMS_LANES + lane) * row + k];
    parts[part * DT_GROUP_SUMS_LANES + k] = total;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lid < n) {
    float total = 0.0f;
    for (uint p = 0; p < DT_GROUP_SIZE / DT_GROUP_SUMS_LANES; ++p) total += parts[p * DT_GROUP_SUMS_LANES + lid];
    sums[lid] = total;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
}

/* Largest value over the group and the smallest index holding it, returned to every work-item. */
DT_DEVICE_FN float dt_group_argmax(DT_LOCAL_PTR float* values, DT_LOCAL_PTR uint* indices, float value, uint index,
                                   uint* argmax) {
  const uint lid = get_local_id(0);
  barrier(CLK_LOCAL_MEM_FENCE);
  values[lid] = value;
  indices[lid] = index;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint stride = DT_GROUP_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride) {
      const float other = values[lid + stride];
      const uint other_index = indices[lid + stride];
      if (other > values[lid] || (other == values[lid] && other_index < indices[lid])) {
        values[lid] = other;
        indices[lid] = other_index;
      }
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  *argmax = indices[0];
  return values[0];
}
#endif
