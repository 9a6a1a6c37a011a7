/* A pose moved about the mesh's centre by a displacement and a rotation vector, both in the object's
 * local frame, stored into a particle's state: the one step of the motion model and the initial draw.
 * Reference: reference::move_about_centre (src/model/particle.cpp). */
#ifndef DT_POSE_MOVE_H
#define DT_POSE_MOVE_H
#include "dt_prelude.h"
#include "dt_quaternion.h"
#include "dt_state.h"

/* Pose (t, q) with its centre moved by q * displacement and the object turned about that centre by
 * exp(rotation) (right-multiplied: local frame), written into s's translation and quaternion. */
DT_DEVICE_FN void dt_store_moved_pose(__global float* s, dt_vec3 t, dt_quat q, dt_vec3 centre, dt_vec3 displacement,
                                      dt_vec3 rotation) {
  const dt_vec3 c = dt_quat_rotate(q, centre);
  const dt_vec3 d = dt_quat_rotate(q, displacement);
  const dt_vec3 moved = dt_vec3_make(t.x + c.x + d.x, t.y + c.y + d.y, t.z + c.z + d.z);
  q = dt_quat_normalize(dt_quat_mul(q, dt_quat_exp(rotation)));
  const dt_vec3 c2 = dt_quat_rotate(q, centre);
  s[DT_TX] = moved.x - c2.x;
  s[DT_TX + 1] = moved.y - c2.y;
  s[DT_TX + 2] = moved.z - c2.z;
  s[DT_QW] = q.w;
  s[DT_QW + 1] = q.x;
  s[DT_QW + 2] = q.y;
  s[DT_QW + 3] = q.z;
}
#endif
