/* A rectangle of image pixels: a pose's box (rasterize.cl's dt_pose_box), a state window, and the
 * pixels weigh visits (dt_weigh.h). */
#ifndef DT_PIXEL_BOX_H
#define DT_PIXEL_BOX_H
#include "dt_prelude.h"

typedef struct {
  uint u0, v0, width, height; /* empty: width or height 0 */
} dt_pixel_box;

/* The smallest box holding both (an empty one adds nothing). */
DT_DEVICE_FN dt_pixel_box dt_box_union(dt_pixel_box a, dt_pixel_box b) {
  if (a.width == 0 || a.height == 0) return b;
  if (b.width == 0 || b.height == 0) return a;
  const uint a_u1 = a.u0 + a.width, a_v1 = a.v0 + a.height, b_u1 = b.u0 + b.width, b_v1 = b.v0 + b.height;
  dt_pixel_box r;
  r.u0 = a.u0 < b.u0 ? a.u0 : b.u0;
  r.v0 = a.v0 < b.v0 ? a.v0 : b.v0;
  r.width = (a_u1 > b_u1 ? a_u1 : b_u1) - r.u0;
  r.height = (a_v1 > b_v1 ? a_v1 : b_v1) - r.v0;
  return r;
}

DT_DEVICE_FN int dt_box_holds(dt_pixel_box box, uint u, uint v) {
  return u - box.u0 < box.width && v - box.v0 < box.height; /* unsigned: left of or above wraps */
}
#endif
