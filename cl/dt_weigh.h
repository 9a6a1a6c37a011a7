/* What weigh.cl and render_weigh.cl share: a particle's group begins and ends the same way, and between
 * them weighs each pixel with dt_weigh_pixel. Reference: ReferenceFilter::weigh_particle. */
#ifndef DT_WEIGH_H
#define DT_WEIGH_H
#include "dt_prelude.h"
#include "dt_group.h"
#include "dt_model.h"
#include "dt_params.h" /* the DT_OCCLUSION codes */
#include "dt_pixel_box.h"
#include "dt_time_index.h"
#include "dt_window.h"

/* Per-pixel time: this frame's time into the table, by the first work-item (no pixel holds now_index
 * while it is written: indices are retired long before they come round). */
DT_DEVICE_FN void dt_weigh_begin(__global float* frame_times, float now, uint now_index) {
#if DT_OCCLUSION == DT_PER_PIXEL_TIME
  if (get_group_id(0) == 0 && get_local_id(0) == 0) frame_times[now_index] = now;
#endif
}

/* The pixels a particle's weigh visits: those its pose can cover (its box) and its state window's
 * (whose state it carries over), in one rectangle; off keeps no state. */
DT_DEVICE_FN dt_pixel_box dt_weigh_box(dt_pixel_box box, dt_window win) {
#if DT_OCCLUSION == DT_OCCLUSION_OFF
  return box;
#else
  return dt_box_union(box, dt_box_make(win.u0, win.v0, win.width, win.height));
#endif
}

/* The group's sum of its particle's pixel terms: the particle's log-likelihood, added to its weight. */
DT_DEVICE_FN void dt_weigh_end(DT_LOCAL_PTR float* scratch, float sum, __global float* log_likelihood,
                               __global float* log_weight, uint particle) {
  sum = dt_group_sum(scratch, sum);
  if (get_local_id(0) == 0) {
    log_likelihood[particle] = sum;
    log_weight[particle] += sum;
  }
}

/* One pixel of one particle's weigh: its log-ratio term, and its occlusion state after the frame
 * written at index `to` of row to_row from the state before it at index `from` of row from_row (its
 * parent's: the last frame's resampling, folded in). Under the state window (dt_window.h) from is -1
 * for a fresh pixel (`initial` at time 0) and to is -1 outside this frame's window (nothing kept).
 * y_hat: the particle's rendered depth there (0: not covered); y: the observed depth. An unused pixel
 * (not covered, or no valid depth) adds 0 and carries its state over (global time: aged by dt). */
DT_DEVICE_FN float dt_weigh_pixel(float y_hat, float y, int from, int to, ulong from_row, ulong to_row,
                                  __global const float* occlusion_from, __global const dt_u16* time_from,
                                  __global float* occlusion_to, __global dt_u16* time_to,
                                  __global const float* frame_times, dt_model m, float initial, float now,
                                  uint now_index, float dt) {
  const int used = y_hat > 0.0f && y > 0.0f && isfinite(y);
  float p = 0.0f;
#if DT_OCCLUSION == DT_GLOBAL_TIME
  /* every pixel ages, covered or not; a fresh one from time 0 */
  p = from >= 0 ? dt_propagate_occlusion(m, occlusion_from[from_row + from], dt)
                : dt_propagate_occlusion(m, initial, now);
  if (!used) {
    if (to >= 0) occlusion_to[to_row + to] = p;
    return 0.0f;
  }
#elif DT_OCCLUSION == DT_PER_PIXEL_TIME
  const float kept = from >= 0 ? occlusion_from[from_row + from] : initial;
  const dt_u16 seen = from >= 0 ? time_from[from_row + from] : DT_CAST(dt_u16, DT_TIME_NEVER);
  if (!used) { /* unchanged: the parent's value and time */
    if (to >= 0) {
      occlusion_to[to_row + to] = kept;
      time_to[to_row + to] = seen;
    }
    return 0.0f;
  }
  p = dt_propagate_occlusion(m, kept, now - frame_times[seen]);
#else
  if (!used) return 0.0f;
#endif
  float posterior;
  const float term = dt_pixel_log_ratio(m, y, y_hat, p, &posterior);
#if DT_OCCLUSION != DT_OCCLUSION_OFF
  if (to >= 0) occlusion_to[to_row + to] = posterior;
#endif
#if DT_OCCLUSION == DT_PER_PIXEL_TIME
  if (to >= 0) time_to[to_row + to] = DT_CAST(dt_u16, now_index);
#endif
  return term;
}

/* Image pixel k = (u, v) of a particle (y_hat drawn there), with its state under the window: its rows
 * hold the window's pixels, read from row from_row (its parent's) and written to row to_row. */
DT_DEVICE_FN float dt_weigh_image_pixel(uint k, dt_u32 u, dt_u32 v, float y_hat, __global const float* observed, dt_window win,
                                        ulong from_row, ulong to_row, __global const float* occlusion_from,
                                        __global const dt_u16* time_from, __global float* occlusion_to,
                                        __global dt_u16* time_to, __global const float* frame_times, dt_model m,
                                        float now, uint now_index, float dt) {
  const int to = dt_window_to(win, u, v);
#if DT_OCCLUSION == DT_OCCLUSION_OFF
  if (!(y_hat > 0.0f)) return 0.0f;
#else
  if (to < 0 && !(y_hat > 0.0f)) return 0.0f; /* neither kept nor weighed */
#endif
  return dt_weigh_pixel(y_hat, y_hat > 0.0f ? observed[k] : 0.0f, dt_window_from(win, to, u, v), to, from_row, to_row,
                        occlusion_from, time_from, occlusion_to, time_to, frame_times, m, win.initial, now,
                        now_index, dt);
}

#endif
