/* The motion model for one particle (MODEL.md "State and motion"; reference: src/model/particle.cpp):
 * propagate.cl runs it a work-item per particle; render_weigh.cl runs it at the start of each particle's
 * group, which saves the frame a launch. */
#ifndef DT_PROPAGATE_H
#define DT_PROPAGATE_H
#include "dt_params.h" /* dt_motion: the per-frame constants of the host's model::motion_step */
#include "dt_pose_move.h"
#include "dt_prelude.h"
#include "philox.h"

DT_DEVICE_FN void dt_propagate_particle(__global float* state, uint i, uint seed_lo, uint seed_hi, uint frame,
                                        dt_motion m) {
  __global float* s = state + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  float n[6];
  dt_normals6((DT_CAST(dt_u64, seed_hi) << 32) | seed_lo, i, frame, DT_STREAM_MOTION, n);
  for (int k = 0; k < 3; ++k) {
    s[DT_VX + k] = m.keep * s[DT_VX + k] + m.linear_std * n[k];
    s[DT_WX + k] = m.keep * s[DT_WX + k] + m.angular_std * n[3 + k];
  }
  dt_quat q;
  q.w = s[DT_QW];
  q.x = s[DT_QW + 1];
  q.y = s[DT_QW + 2];
  q.z = s[DT_QW + 3];
  /* The centre moves by v dt along the object's axes; the object turns about its centre by w dt. */
  dt_store_moved_pose(s, dt_vec3_make(s[DT_TX], s[DT_TX + 1], s[DT_TX + 2]), q,
                      dt_vec3_make(m.centre_x, m.centre_y, m.centre_z),
                      dt_vec3_make(s[DT_VX] * m.dt, s[DT_VX + 1] * m.dt, s[DT_VX + 2] * m.dt),
                      dt_vec3_make(s[DT_WX] * m.dt, s[DT_WX + 1] * m.dt, s[DT_WX + 2] * m.dt));
}

#endif
