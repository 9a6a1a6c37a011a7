/* Where a pixel's occlusion state lies in a particle's row under the state window (dt_params.h's
 * dt_window): weigh's reads and writes and the refinement's prior. Reference: ReferenceFilter's
 * window handling (model::StateWindow). */
#ifndef DT_WINDOW_H
#define DT_WINDOW_H
#include "dt_prelude.h"
#include "dt_params.h"

/* Index of image pixel (u, v) in a row of a width x height window at (u0, v0), or -1 where the window
 * does not hold it (unsigned differences: left of or above the window wraps to a large value). */
DT_DEVICE_FN int dt_window_index(dt_u32 width, dt_u32 height, dt_u32 u0, dt_u32 v0, dt_u32 u, dt_u32 v) {
  const dt_u32 x = u - u0, y = v - v0;
  return x < width && y < height ? DT_CAST(int, y * width + x) : -1;
}

/* Values in a row written this frame, and in a row read (the last frame's window). */
DT_DEVICE_FN ulong dt_window_row(dt_window w) {
  return DT_CAST(ulong, w.width) * w.height;
}
DT_DEVICE_FN ulong dt_window_last_row(dt_window w) {
  return DT_CAST(ulong, w.last_width) * w.last_height;
}

/* DT_WHOLE_IMAGE_STATE 1: the host's promise that the window is the whole image (the default
 * configuration), so that a pixel's index is its own and weigh's per-pixel tests go. */
#ifndef DT_WHOLE_IMAGE_STATE
#define DT_WHOLE_IMAGE_STATE 0
#endif

/* Image pixel (u, v)'s index in this frame's rows (written), or -1 outside the window. */
DT_DEVICE_FN int dt_window_to(dt_window w, dt_u32 u, dt_u32 v) {
#if DT_WHOLE_IMAGE_STATE
  return DT_CAST(int, v * w.width + u);
#else
  return dt_window_index(w.width, w.height, w.u0, w.v0, u, v);
#endif
}

/* Image pixel (u, v)'s index in the rows read (the last frame's window), given its index `to` in this
 * frame's (dt_window_to), or -1 where it is fresh: outside this frame's window or new to it. */
DT_DEVICE_FN int dt_window_from(dt_window w, int to, dt_u32 u, dt_u32 v) {
#if DT_WHOLE_IMAGE_STATE
  return to;
#else
  return to < 0 ? -1 : dt_window_index(w.last_width, w.last_height, w.last_u0, w.last_v0, u, v);
#endif
}

#endif
