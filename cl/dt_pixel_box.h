/* A rectangle of image pixels: a pose's box (rasterize.cl's dt_pose_box), a state window, and the
 * pixels weigh visits (dt_weigh.h); and the walk that hands a rectangle's pixels to a group's
 * work-items in turn (dt_pixel_place, dt_pixel_step: DT_GROUP_SIZE of the including program). */
#ifndef DT_PIXEL_BOX_H
#define DT_PIXEL_BOX_H
#include "dt_prelude.h"

typedef struct {
  uint u0, v0, width, height; /* empty: width or height 0 */
} dt_pixel_box;

DT_DEVICE_FN dt_pixel_box dt_box_make(uint u0, uint v0, uint width, uint height) {
  dt_pixel_box r;
  r.u0 = u0;
  r.v0 = v0;
  r.width = width;
  r.height = height;
  return r;
}

/* No pixels: the band argument of the drawing functions that do not draw into work-group memory. */
DT_DEVICE_FN dt_pixel_box dt_no_band(void) {
  return dt_box_make(0, 0, 0, 0);
}

/* As 4 words (u0, v0, width, height) at box i of `boxes`: rasterize.cl's boxes for weigh.cl. */
DT_DEVICE_FN void dt_box_store(__global uint* boxes, uint i, dt_pixel_box box) {
  __global uint* at = boxes + 4 * DT_CAST(ulong, i);
  at[0] = box.u0;
  at[1] = box.v0;
  at[2] = box.width;
  at[3] = box.height;
}
DT_DEVICE_FN dt_pixel_box dt_box_load(__global const uint* boxes, uint i) {
  __global const uint* at = boxes + 4 * DT_CAST(ulong, i);
  return dt_box_make(at[0], at[1], at[2], at[3]);
}

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
/* (x, y) of pixel k of a rectangle `width` wide, for a loop that then steps k by DT_GROUP_SIZE with
 * dt_pixel_step (no division per pixel: at 80x60 one in each of weigh's iterations cost more than the
 * pixel's term). */
DT_DEVICE_FN void dt_pixel_place(dt_u32 k, dt_u32 width, dt_u32* u, dt_u32* v) {
  *u = k % width;
  *v = k / width;
}
DT_DEVICE_FN void dt_pixel_step(dt_u32 width, dt_u32* u, dt_u32* v) {
  *u += DT_GROUP_SIZE % width;
  *v += DT_GROUP_SIZE / width;
  if (*u >= width) {
    *u -= width;
    *v += 1;
  }
}
#endif
