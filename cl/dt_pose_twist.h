/* A particle's pose in a work-item's registers, loaded from and stored into its state (dt_state.h),
 * and moved by a camera-frame twist about the mesh's centre: the refinement's steps (dt_refine.h) and
 * the correction that moves the whole cloud after it (resample.cl's resample_particles).
 * Reference: reference::apply_twist. */
#ifndef DT_POSE_TWIST_H
#define DT_POSE_TWIST_H
#include "dt_prelude.h"
#include "dt_quaternion.h"
#include "dt_state.h"

/* Pose as translation and unit quaternion, in a work-item's registers. */
typedef struct {
  dt_vec3 t;
  dt_quat q;
} dt_pose;

DT_DEVICE_FN dt_vec3 dt_pose_centre(dt_pose p, dt_vec3 centre) {
  const dt_vec3 c = dt_quat_rotate(p.q, centre);
  return dt_vec3_make(c.x + p.t.x, c.y + p.t.y, c.z + p.t.z);
}

/* The pose moved by the camera-frame twist (dt, dw) about centre (object frame). */
DT_DEVICE_FN dt_pose dt_apply_twist(dt_pose p, dt_vec3 centre, const float* twist) {
  const dt_vec3 c = dt_pose_centre(p, centre);
  dt_pose r;
  r.q = dt_quat_normalize(dt_quat_mul(dt_quat_exp(dt_vec3_make(twist[3], twist[4], twist[5])), p.q));
  const dt_vec3 rc = dt_quat_rotate(r.q, centre);
  r.t = dt_vec3_make(c.x + twist[0] - rc.x, c.y + twist[1] - rc.y, c.z + twist[2] - rc.z);
  return r;
}

DT_DEVICE_FN void dt_store_pose(__global float* s, dt_pose p) {
  s[DT_TX] = p.t.x;
  s[DT_TX + 1] = p.t.y;
  s[DT_TX + 2] = p.t.z;
  s[DT_QW] = p.q.w;
  s[DT_QW + 1] = p.q.x;
  s[DT_QW + 2] = p.q.y;
  s[DT_QW + 3] = p.q.z;
}

DT_DEVICE_FN dt_pose dt_load_pose(__global const float* s) {
  dt_pose p;
  p.t = dt_vec3_make(s[DT_TX], s[DT_TX + 1], s[DT_TX + 2]);
  p.q.w = s[DT_QW];
  p.q.x = s[DT_QW + 1];
  p.q.y = s[DT_QW + 2];
  p.q.z = s[DT_QW + 3];
  return p;
}
#endif
