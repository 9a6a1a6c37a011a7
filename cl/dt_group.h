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
