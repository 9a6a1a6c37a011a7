/* The filter's starting state drawn and filled on the device, so that start-up never builds a host
 * copy of particles x pixels values. Reference: ReferenceFilter::initialize, initial_particle. */
#include "dt_prelude.h"
#include "dt_pose_move.h"
#include "philox.h"
#include "dt_params.h" /* dt_initial */

/* Particle i: pose i % mode_count of modes (7 floats each: t xyz, q wxyz) moved about the mesh's
 * centre by the spread times six normals of (seed, i, frame 0, DT_STREAM_INIT), at rest; the same
 * draws as the reference's. */
__kernel void initialize_particles(__global float* state, uint count, uint seed_lo, uint seed_hi,
                                   __global const float* modes, dt_initial a) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  float n[6];
  dt_normals6((DT_CAST(dt_u64, seed_hi) << 32) | seed_lo, i, 0u, DT_STREAM_INIT, n);
  __global const float* mode = modes + 7 * (i % a.mode_count);
  dt_quat q;
  q.w = mode[3];
  q.x = mode[4];
  q.y = mode[5];
  q.z = mode[6];
  __global float* s = state + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  for (int k = 0; k < DT_STATE_STRIDE; ++k) s[k] = 0.0f; /* at rest */
  dt_store_moved_pose(s, dt_vec3_make(mode[0], mode[1], mode[2]), q, dt_vec3_make(a.centre_x, a.centre_y, a.centre_z),
                      dt_vec3_make(a.metres * n[0], a.metres * n[1], a.metres * n[2]),
                      dt_vec3_make(a.radians * n[3], a.radians * n[4], a.radians * n[5]));
}

/* Every particle's `pixels` values set to `value`: a work-group per particle, so that buffers of
 * more than 2^32 values (a million particles at 80x60) need no 64-bit work-item ids. */
__kernel void fill_per_particle(__global float* values, uint pixels, float value) {
  __global float* row = values + DT_CAST(ulong, get_group_id(0)) * pixels;
  for (uint k = get_local_id(0); k < pixels; k += DT_GROUP_SIZE) row[k] = value;
}
