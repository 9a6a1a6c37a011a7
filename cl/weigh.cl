/* Occlusion-aware log-likelihood: a work-group per particle, consecutive pixels to consecutive
 * work-items (the thesis' layout), a group sum at the end. Compile-time choices:
 *   DT_GROUP_SIZE     work-items per group (power of two)
 *   DT_OCCLUSION      0 per-pixel time, 1 global time, 2 off
 * The atlas lies in the renderer's page layout (dt_atlas.h); occlusion state is particle-major.
 * With keep_prior, each updated pixel's occlusion probability before its Bayes update goes to prior
 * (particle-major too): the pose refinement's occlusion map (refine.cl).
 * Per-pixel time keeps each pixel's last frame as an index into frame_times (dt_time_index.h); this
 * frame is now_index, whose time (now) the first work-item writes into the table: no pixel holds that
 * index while it is written (indices are retired long before they come round).
 * Reference: ReferenceFilter::weigh_particle. */
#include "dt_prelude.h"
#include "dt_model.h"
#include "dt_group.h"
#include "dt_atlas.h"
#include "dt_params.h" /* the DT_OCCLUSION codes */
#include "dt_time_index.h"

__kernel void weigh(__global const float* atlas, __global const float* observed, __global float* occlusion,
                    __global dt_u16* occlusion_time, __global float* frame_times, __global float* log_likelihood,
                    __global float* log_weight, uint pixels, dt_model m, float now, uint now_index, float dt,
                    dt_atlas_layout layout, __global float* prior, uint keep_prior) {
  __local float scratch[DT_GROUP_SIZE];
  const uint particle = get_group_id(0);
#if DT_OCCLUSION == DT_PER_PIXEL_TIME
  if (particle == 0 && get_local_id(0) == 0) frame_times[now_index] = now;
#endif
  const ulong base = DT_CAST(ulong, particle) * pixels;
  const ulong tile = dt_atlas_tile_start(layout, particle);
  float sum = 0.0f;
  for (uint k = get_local_id(0); k < pixels; k += DT_GROUP_SIZE) {
    float p = 0.0f;
#if DT_OCCLUSION == DT_GLOBAL_TIME
    p = dt_propagate_occlusion(m, occlusion[base + k], dt);
    occlusion[base + k] = p; /* every pixel ages, covered or not */
#endif
    const float y_hat = atlas[dt_atlas_pixel(layout, tile, k)];
    const float y = observed[k];
    if (!(y_hat > 0.0f) || !(y > 0.0f) || !isfinite(y)) continue; /* adds 0 */
#if DT_OCCLUSION == DT_PER_PIXEL_TIME
    p = dt_propagate_occlusion(m, occlusion[base + k], now - frame_times[occlusion_time[base + k]]);
#endif
    float posterior;
    sum += dt_pixel_log_ratio(m, y, y_hat, p, &posterior);
#if DT_OCCLUSION != DT_OCCLUSION_OFF
    if (keep_prior) prior[base + k] = p;
    occlusion[base + k] = posterior;
#endif
#if DT_OCCLUSION == DT_PER_PIXEL_TIME
    occlusion_time[base + k] = DT_CAST(dt_u16, now_index);
#endif
  }
  sum = dt_group_sum(scratch, sum);
  if (get_local_id(0) == 0) {
    log_likelihood[particle] = sum;
    log_weight[particle] += sum;
  }
}
