/* Normalization, degeneracy and the estimate, in one work-group of DT_GROUP_SIZE that strides over
 * all particles: log-sum-exp, ESS, KL from uniform, the weighted mean centre and velocities, and the
 * rotation mean in the tangent space of the heaviest particle (4 Karcher iterations), and the
 * resampling decision (KL > kl_threshold) that resample.cl's kernels read. With the effective sample
 * size near 1 nearly every weight is exactly 0 in float, and such a particle adds exactly 0 to every
 * weighted sum (its state is finite), so its state is not read: the passes over the states then cost
 * a read of the weights (one group strides over all particles: at a million particles each state read
 * was a wait on memory).
 * Reference: summarize_log_weights and weighted_mean_pose. */
#include "dt_prelude.h"
#include "dt_quaternion.h"
#include "dt_state.h"
#include "dt_group.h"

DT_DEVICE_FN dt_quat dt_load_rotation(__global const float* state, uint i) {
  __global const float* s = state + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  dt_quat q;
  q.w = s[DT_QW];
  q.x = s[DT_QW + 1];
  q.y = s[DT_QW + 2];
  q.z = s[DT_QW + 3];
  return q;
}

__kernel void summarize(__global const float* state, __global const float* log_weight,
                        __global const float* log_likelihood, __global float* weights, __global float* estimate,
                        uint count, float centre_x, float centre_y, float centre_z, float kl_threshold) {
  __local float scratch[DT_GROUP_SIZE];
  __local uint scratch_index[DT_GROUP_SIZE];
  const uint lid = get_local_id(0);
  const dt_vec3 centre = dt_vec3_make(centre_x, centre_y, centre_z);

  float best = DT_LOWEST, best_ll = DT_LOWEST;
  uint best_index = count;
  for (uint i = lid; i < count; i += DT_GROUP_SIZE) {
    if (log_weight[i] > best) {
      best = log_weight[i];
      best_index = i;
    }
    best_ll = fmax(best_ll, log_likelihood[i]);
  }
  uint heaviest;
  const float max_log_weight = dt_group_argmax(scratch, scratch_index, best, best_index, &heaviest);
  uint unused;
  const float max_ll = dt_group_argmax(scratch, scratch_index, best_ll, 0, &unused);

  float sum = 0.0f;
  for (uint i = lid; i < count; i += DT_GROUP_SIZE) sum += exp(log_weight[i] - max_log_weight);
  const float total = dt_group_sum(scratch, sum);

  /* Weighted sums: squares, entropy, mean log-likelihood, centre (3), velocities (6). */
  float acc[12];
  for (int k = 0; k < 12; ++k) acc[k] = 0.0f;
  for (uint i = lid; i < count; i += DT_GROUP_SIZE) {
    const float w = exp(log_weight[i] - max_log_weight) / total;
    weights[i] = w;
    if (w == 0.0f) continue; /* adds exactly 0 */
    __global const float* s = state + DT_CAST(ulong, i) * DT_STATE_STRIDE;
    const dt_vec3 c = dt_quat_rotate(dt_load_rotation(state, i), centre);
    acc[0] += w * w;
    if (w > 0.0f) acc[1] -= w * log(w);
    acc[2] += w * log_likelihood[i];
    acc[3] += w * (s[DT_TX] + c.x);
    acc[4] += w * (s[DT_TX + 1] + c.y);
    acc[5] += w * (s[DT_TX + 2] + c.z);
    for (int k = 0; k < 6; ++k) acc[6 + k] += w * s[DT_VX + k];
  }
  for (int k = 0; k < 12; ++k) acc[k] = dt_group_sum(scratch, acc[k]);

  dt_quat mean = dt_load_rotation(state, heaviest);
  for (int iteration = 0; iteration < 4; ++iteration) {
    float step[3] = {0.0f, 0.0f, 0.0f};
    for (uint i = lid; i < count; i += DT_GROUP_SIZE) {
      const float w = weights[i];
      if (w == 0.0f) continue; /* adds exactly 0 */
      const dt_vec3 d = dt_quat_log(dt_quat_mul(dt_quat_conj(mean), dt_load_rotation(state, i)));
      step[0] += w * d.x;
      step[1] += w * d.y;
      step[2] += w * d.z;
    }
    for (int k = 0; k < 3; ++k) step[k] = dt_group_sum(scratch, step[k]);
    mean = dt_quat_normalize(dt_quat_mul(mean, dt_quat_exp(dt_vec3_make(step[0], step[1], step[2]))));
  }

  if (lid == 0) {
    const dt_vec3 c = dt_quat_rotate(mean, centre);
    estimate[DT_EST_TX] = acc[3] - c.x;
    estimate[DT_EST_TX + 1] = acc[4] - c.y;
    estimate[DT_EST_TX + 2] = acc[5] - c.z;
    estimate[DT_EST_QW] = mean.w;
    estimate[DT_EST_QW + 1] = mean.x;
    estimate[DT_EST_QW + 2] = mean.y;
    estimate[DT_EST_QW + 3] = mean.z;
    for (int k = 0; k < 6; ++k) estimate[DT_EST_VX + k] = acc[6 + k];
    estimate[DT_EST_ESS] = 1.0f / acc[0];
    const float kl = log(DT_CAST(float, count)) - acc[1];
    estimate[DT_EST_KL] = kl;
    estimate[DT_EST_RESAMPLE] = kl > kl_threshold ? 1.0f : 0.0f;
    estimate[DT_EST_MAX_LL] = max_ll;
    estimate[DT_EST_MEAN_LL] = acc[2];
    estimate[DT_EST_HEAVIEST] = dt_as_float(heaviest); /* for refine.cl */
  }
}
