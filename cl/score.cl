/* Stateless scoring of a batch of poses for global search: a work-group per pose, the same
 * per-pixel terms as weigh.cl with every pixel's occlusion probability at the fresh prior p, and
 * nothing written but the score. DT_GROUP_SIZE: work-items per group (power of two).
 * Reference: reference::score_pose. */
#include "dt_prelude.h"
#include "dt_model.h"
#include "dt_group.h"
#include "dt_atlas.h"

__kernel void score(__global const float* atlas, __global const float* observed, __global float* scores, uint pixels,
                    dt_model m, float p, dt_atlas_layout layout) {
  __local float scratch[DT_GROUP_SIZE];
  const uint pose = get_group_id(0);
  const ulong tile = dt_atlas_tile_start(layout, pose);
  float sum = 0.0f;
  for (uint k = get_local_id(0); k < pixels; k += DT_GROUP_SIZE) {
    const float y_hat = atlas[dt_atlas_pixel(layout, tile, k)];
    const float y = observed[k];
    if (!(y_hat > 0.0f) || !(y > 0.0f) || !isfinite(y)) continue; /* adds 0 */
    float posterior;
    sum += dt_pixel_log_ratio(m, y, y_hat, p, &posterior);
  }
  sum = dt_group_sum(scratch, sum);
  if (get_local_id(0) == 0) scores[pose] = sum;
}
