/* summarize.cl's work as a function of one work-group of DT_GROUP_SIZE: summarize.cl's kernel calls
 * it, and refine_spread.cl's refine_one_launch before the fit (one launch for both). The locals are
 * the caller's: scratch and scratch_index DT_GROUP_SIZE each, sums DT_GROUP_SUMS_SCRATCH(DT_WEIGHTED_SUMS). */
#ifndef DT_SUMMARIZE_H
#define DT_SUMMARIZE_H
#include "dt_estimate.h"
#include "dt_group.h"
#include "dt_prelude.h"
#include "dt_quaternion.h"
#include "dt_state.h"
#include "dt_summary.h" /* DT_KARCHER_STEPS */

DT_DEVICE_FN void dt_summarize(__global const float* state, __global const float* log_weight,
                               __global const float* log_likelihood, __global float* weights, __global float* estimate,
                               uint count, dt_vec3 centre, float kl_threshold, uint karcher_steps,
                               DT_LOCAL_PTR float* scratch, DT_LOCAL_PTR uint* scratch_index,
                               DT_LOCAL_PTR float* sums) {
  const uint lid = get_local_id(0);

  uint heaviest;
  float max_ll;
  const float max_log_weight = dt_group_max_weight(scratch, scratch_index, log_weight, log_likelihood, lid,
                                                   DT_GROUP_SIZE, count, &heaviest, &max_ll);

  float sum = 0.0f;
  for (uint i = lid; i < count; i += DT_GROUP_SIZE) sum += exp(log_weight[i] - max_log_weight);
  const float total = dt_group_sum(scratch, sum);

  /* Weighted sums: squares, entropy, mean log-likelihood, centre (3), velocities (6). */
  float acc[DT_WEIGHTED_SUMS];
  for (int k = 0; k < DT_WEIGHTED_SUMS; ++k) acc[k] = 0.0f;
  for (uint i = lid; i < count; i += DT_GROUP_SIZE) {
    const float w = exp(log_weight[i] - max_log_weight) / total;
    weights[i] = w;
    if (w > 0.0f) dt_add_weighted(acc, state, log_likelihood, i, w, centre); /* 0 adds exactly 0 */
  }
  dt_group_sums(acc, DT_WEIGHTED_SUMS, sums);
  for (int k = 0; k < DT_WEIGHTED_SUMS; ++k) acc[k] = sums[k];

  dt_quat mean = dt_load_rotation(state, heaviest);
  for (uint iteration = 0; iteration < karcher_steps; ++iteration) {
    float step[3] = {0.0f, 0.0f, 0.0f};
    for (uint i = lid; i < count; i += DT_GROUP_SIZE)
      if (weights[i] > 0.0f) dt_add_karcher_step(step, state, i, weights[i], mean); /* 0 adds exactly 0 */
    dt_group_sums(step, 3, sums);
    for (int k = 0; k < 3; ++k) step[k] = sums[k];
    mean = dt_quat_normalize(dt_quat_mul(mean, dt_quat_exp(dt_vec3_make(step[0], step[1], step[2]))));
  }

  if (lid == 0) dt_write_estimate(estimate, acc, mean, centre, count, max_ll, heaviest, kl_threshold);
}

#endif
