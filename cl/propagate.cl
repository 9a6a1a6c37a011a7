/* Motion model: one work-item per particle (dt_propagate.h). Where the atlas is drawn inside weigh,
 * render_weigh.cl propagates instead and this kernel is not launched. */
#include "dt_propagate.h"

__kernel void propagate(__global float* state, uint count, uint seed_lo, uint seed_hi, uint frame, dt_motion m) {
  const uint i = get_global_id(0);
  if (i < count) dt_propagate_particle(state, i, seed_lo, seed_hi, frame, m);
}
