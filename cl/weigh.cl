/* Occlusion-aware log-likelihood: a work-group per particle, consecutive pixels to consecutive
 * work-items (the thesis' layout), a group sum at the end. Compile-time choices:
 *   DT_GROUP_SIZE     work-items per group (power of two)
 *   DT_OCCLUSION      0 per-pixel time, 1 global time, 2 off
 * The atlas lies in the renderer's page layout (dt_atlas.h); occlusion state is particle-major.
 * The last frame's resampling is folded in here: particle i's occlusion state before this frame is
 * row parents[i] of (occlusion_from, time_from) (the identity where it did not resample), and its
 * state after this frame's Bayes update goes to row i of (occlusion_to, time_to), every pixel
 * written, so that no pass copies whole rows between frames (the host swaps the two buffers). With
 * an effective sample size near 1 most children read one parent's row, which stays in cache.
 * Per-pixel time keeps each pixel's last frame as an index into frame_times (dt_time_index.h); this
 * frame is now_index, whose time (now) the first work-item writes into the table: no pixel holds that
 * index while it is written (indices are retired long before they come round).
 * The rows hold the state window's pixels (dt_window.h; the whole image by default); a group visits
 * only the rectangle around its tile's box (rasterize.cl's boxes, where it wrote them) and the
 * window, its pixels handed to the work-items in turn (as render_weigh.cl: the same sums).
 * Group g weighs particle first + g against tile g (an atlas of fewer tiles than particles is drawn and
 * weighed in turns: TrackerConfig::atlas_particles); boxes are the particles'.
 * Reference: ReferenceFilter::weigh_particle (and its resampling's gather). */
#include "dt_prelude.h"
#include "dt_launch.h"
#ifndef DT_GROUP_SIZE
#define DT_GROUP_SIZE DT_FILTER_GROUP
#endif
#include "dt_atlas.h"
#include "dt_weigh.h" /* shared with render_weigh.cl */

__kernel void weigh(__global const float* atlas, __global const float* observed, __global const uint* parents,
                    __global const float* occlusion_from, __global const dt_u16* time_from,
                    __global float* occlusion_to, __global dt_u16* time_to, __global float* frame_times,
                    __global float* log_likelihood, __global float* log_weight, uint pixels, dt_model m, float now,
                    uint now_index, float dt, dt_atlas_layout layout, dt_window win, __global const uint* boxes,
                    uint boxed, uint first) {
  __local float scratch[DT_GROUP_SIZE];
  const uint particle = first + get_group_id(0), lid = get_local_id(0), width = win.image_width;
  dt_weigh_begin(frame_times, now, now_index);
  /* The tile's box (rasterize.cl with boxed: nothing is drawn outside it, and it is not cleared there)
   * and the state window's pixels; the whole image without boxes. */
  const dt_pixel_box box = boxed ? dt_box_load(boxes, particle) : dt_box_make(0, 0, width, pixels / width);
  const ulong from = DT_CAST(ulong, parents[particle]) * dt_window_last_row(win),
              to = DT_CAST(ulong, particle) * dt_window_row(win);
  const ulong tile = dt_atlas_tile_start(layout, get_group_id(0));
  const dt_pixel_box visited = dt_weigh_box(box, win);
  float sum = 0.0f;
  /* The rectangle's pixels to the work-items in turn, as the whole image's in a plain loop. */
  const uint visits = visited.width * visited.height;
  dt_u32 x = 0, y = 0;
  if (visits > 0) dt_pixel_place(lid, visited.width, &x, &y);
  for (uint b = lid; b < visits; b += DT_GROUP_SIZE, dt_pixel_step(visited.width, &x, &y)) {
    const dt_u32 u = visited.u0 + x, v = visited.v0 + y;
    const uint k = v * width + u;
    const float y_hat = dt_box_holds(box, u, v) ? atlas[dt_atlas_pixel(layout, tile, k)] : 0.0f;
    sum += dt_weigh_image_pixel(k, u, v, y_hat, observed, win, from, to, occlusion_from, time_from, occlusion_to,
                                time_to, frame_times, m, now, now_index, dt);
  }
  dt_weigh_end(scratch, sum, log_likelihood, log_weight, particle);
}
