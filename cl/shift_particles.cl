/* The cloud follows the refinement (refine.cl, refine_spread.cl): every particle moved by the
 * correction twist that put the heaviest particle on the refined pose. Reference: ReferenceFilter::refine. */
#include "dt_refine.h"

/* Every particle moved by the same twist about its own centre: the cloud follows the refinement.
 * from and to may be the same buffer; velocities are copied unchanged. */
__kernel void shift_particles(__global const float* from, __global float* to, uint count,
                              __global const float* correction, float centre_x, float centre_y, float centre_z) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  __global const float* s = from + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  __global float* d = to + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  const float twist[6] = {correction[0], correction[1], correction[2], correction[3], correction[4], correction[5]};
  const dt_pose moved = dt_apply_twist(dt_load_pose(s), dt_vec3_make(centre_x, centre_y, centre_z), twist);
  for (int k = DT_VX; k < DT_STATE_STRIDE; ++k) d[k] = s[k];
  dt_store_pose(d, moved);
}
