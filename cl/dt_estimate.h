/* The pieces of the frame's summary that summarize.cl (one group) and summarize_wide.cl (many) share:
 * a particle's rotation, its share of the weighted sums and of a Karcher step, and the estimate
 * written from the totals. Reference: summarize_log_weights and weighted_mean_pose. */
#ifndef DT_ESTIMATE_H
#define DT_ESTIMATE_H
#include "dt_prelude.h"
#include "dt_group.h"
#include "dt_quaternion.h"
#include "dt_state.h"

#define DT_WEIGHTED_SUMS 12 /* squares, entropy, mean log-likelihood, centre (3), velocities (6) */

DT_DEVICE_FN dt_quat dt_load_rotation(__global const float* state, uint i) {
  __global const float* s = state + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  dt_quat q;
  q.w = s[DT_QW];
  q.x = s[DT_QW + 1];
  q.y = s[DT_QW + 2];
  q.z = s[DT_QW + 3];
  return q;
}

/* Over the group's particles first, first + stride, ... below count: the largest log weight (returned,
 * with the first particle holding it in *heaviest; count where the group has none) and the largest
 * log-likelihood (*max_ll), to every work-item. */
DT_DEVICE_FN float dt_group_max_weight(DT_LOCAL_PTR float* scratch, DT_LOCAL_PTR uint* scratch_index,
                                       __global const float* log_weight, __global const float* log_likelihood,
                                       uint first, uint stride, uint count, uint* heaviest, float* max_ll) {
  float best = DT_LOWEST, best_ll = DT_LOWEST;
  uint best_index = count;
  for (uint i = first; i < count; i += stride) {
    if (log_weight[i] > best) {
      best = log_weight[i];
      best_index = i;
    }
    best_ll = fmax(best_ll, log_likelihood[i]);
  }
  const float max_log_weight = dt_group_argmax(scratch, scratch_index, best, best_index, heaviest);
  uint unused;
  *max_ll = dt_group_argmax(scratch, scratch_index, best_ll, 0, &unused);
  return max_log_weight;
}

/* Particle i's share (weight w > 0) of the weighted sums. */
DT_DEVICE_FN void dt_add_weighted(float* acc, __global const float* state, __global const float* log_likelihood, uint i,
                                  float w, dt_vec3 centre) {
  __global const float* s = state + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  const dt_vec3 c = dt_quat_rotate(dt_load_rotation(state, i), centre);
  acc[0] += w * w;
  acc[1] -= w * log(w);
  acc[2] += w * log_likelihood[i];
  acc[3] += w * (s[DT_TX] + c.x);
  acc[4] += w * (s[DT_TX + 1] + c.y);
  acc[5] += w * (s[DT_TX + 2] + c.z);
  for (int k = 0; k < 6; ++k) acc[6 + k] += w * s[DT_VX + k];
}

/* Particle i's share (weight w) of the Karcher step about mean. */
DT_DEVICE_FN void dt_add_karcher_step(float* step, __global const float* state, uint i, float w, dt_quat mean) {
  const dt_vec3 d = dt_quat_log(dt_quat_mul(dt_quat_conj(mean), dt_load_rotation(state, i)));
  step[0] += w * d.x;
  step[1] += w * d.y;
  step[2] += w * d.z;
}

/* The estimate and the resampling decision (KL > kl_threshold) from the totals. */
DT_DEVICE_FN void dt_write_estimate(__global float* estimate, const float* acc, dt_quat mean, dt_vec3 centre,
                                    uint count, float max_ll, uint heaviest, float kl_threshold) {
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
#endif
