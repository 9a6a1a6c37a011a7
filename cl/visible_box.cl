/* The box of each pose's visible surface points, for a detector's box to be compared with in global
 * search: a work-group per pose projects the mesh's vertices, leaves out those behind the camera, those
 * whose pixel (the projection rounded) lies outside the image, and those hidden there (a valid depth
 * nearer than the point by more than pixel_sigmas sigma(y)), and reduces the rest's image coordinates to
 * their least and largest. Writes u0, v0, u1, v1 per pose (continuous coordinates, pixel centres at whole
 * numbers); u1 < u0 where no point is visible. DT_GROUP_SIZE: work-items per group (power of two).
 * Reference: search::visible_box. */
#include "dt_prelude.h"
#include "dt_model.h"
#include "dt_group.h"
#include "dt_estimate.h" /* dt_load_rotation */

__kernel void visible_box(__global const float* states, __global const float* vertices, uint vertex_count,
                          __global const float* observed, dt_camera camera, dt_model m, float pixel_sigmas,
                          __global float* boxes) {
  __local float scratch[DT_GROUP_SIZE];
  const uint pose = get_group_id(0);
  __global const float* s = states + DT_CAST(ulong, pose) * DT_STATE_STRIDE;
  const dt_quat q = dt_quat_normalize(dt_load_rotation(states, pose));
  /* The least u and v kept as the largest -u and -v, so that one reduction serves all four. */
  float neg_u0 = DT_LOWEST, neg_v0 = DT_LOWEST, u1 = DT_LOWEST, v1 = DT_LOWEST;
  for (uint k = get_local_id(0); k < vertex_count; k += DT_GROUP_SIZE) {
    __global const float* x = vertices + 3 * DT_CAST(ulong, k);
    const dt_vec3 r = dt_quat_rotate(q, dt_vec3_make(x[0], x[1], x[2]));
    const float px = r.x + s[DT_TX], py = r.y + s[DT_TX + 1], pz = r.z + s[DT_TX + 2];
    if (!(pz > 0.0f)) continue;
    const float u = camera.fx * px / pz + camera.cx, v = camera.fy * py / pz + camera.cy;
    const float pixel_u = round(u), pixel_v = round(v);
    if (!(pixel_u >= 0.0f && pixel_v >= 0.0f && pixel_u < DT_CAST(float, camera.width) &&
          pixel_v < DT_CAST(float, camera.height)))
      continue;
    const float y = observed[DT_CAST(uint, pixel_v) * camera.width + DT_CAST(uint, pixel_u)];
    if (y > 0.0f && isfinite(y) && y < pz - pixel_sigmas * dt_depth_sigma(m, y)) continue; /* hidden */
    neg_u0 = fmax(neg_u0, -u);
    neg_v0 = fmax(neg_v0, -v);
    u1 = fmax(u1, u);
    v1 = fmax(v1, v);
  }
  neg_u0 = dt_group_max(scratch, neg_u0);
  neg_v0 = dt_group_max(scratch, neg_v0);
  u1 = dt_group_max(scratch, u1);
  v1 = dt_group_max(scratch, v1);
  if (get_local_id(0) == 0) {
    __global float* box = boxes + 4 * DT_CAST(ulong, pose);
    const int any = u1 > DT_LOWEST;
    box[0] = any ? -neg_u0 : 0.0f;
    box[1] = any ? -neg_v0 : 0.0f;
    box[2] = any ? u1 : -1.0f;
    box[3] = any ? v1 : -1.0f;
  }
}
