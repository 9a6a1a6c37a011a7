/* summarize.cl's normalization, degeneracy and estimate for large clouds, spread over the whole device:
 * each pass over the particles is a kernel of many work-groups that leaves one row of partial results
 * per group, and every group of a later pass combines those rows the same way (a group reduction in
 * a fixed order: the same floats in every group and every run). One group striding over a million
 * particles waited on memory for ~10 ms a frame on the H200 (20 on NVIDIA OpenCL); these passes take
 * microseconds. Launched in this order (WideSummary, src/filter/wide_summary.cpp):
 *   summarize_max       each group's largest log weight (and the first particle holding it) and largest
 *                       log-likelihood
 *   summarize_sum       each group's sum of exp(log weight - the largest)
 *   summarize_weights   the normalized weights, and each group's weighted sums (squares, entropy, mean
 *                       log-likelihood, centre, velocities)
 *   summarize_karcher   4 times: each group's share of a Karcher step of the rotation mean, from the
 *                       heaviest particle's rotation and the steps before it
 *   summarize_finish    one group: the estimate and the resampling decision, as summarize.cl writes them
 * The partial rows: dt_summary.h.
 * DT_GROUP_SIZE: work-items per group (power of two). Reference: summarize_log_weights and
 * weighted_mean_pose. */
#include "dt_prelude.h"
#include "dt_estimate.h"
#include "dt_group.h"
#include "dt_quaternion.h"
#include "dt_state.h"
#include "dt_summary.h"

/* The sum of one field's partials over all groups, returned to every work-item (fixed order). */
DT_DEVICE_FN float dt_partials_sum(DT_LOCAL_PTR float* scratch, __global const float* partials, uint field,
                                   uint groups) {
  float sum = 0.0f;
  for (uint g = get_local_id(0); g < groups; g += DT_GROUP_SIZE) sum += partials[field * groups + g];
  return dt_group_sum(scratch, sum);
}

/* The largest log weight over all groups and the first particle holding it. */
DT_DEVICE_FN float dt_partials_max(DT_LOCAL_PTR float* scratch, DT_LOCAL_PTR uint* scratch_index,
                                   __global const float* partials, uint groups, uint* heaviest) {
  float best = DT_LOWEST;
  uint best_index = 0xffffffffu;
  for (uint g = get_local_id(0); g < groups; g += DT_GROUP_SIZE) {
    const float value = partials[DT_PARTIAL_MAX * groups + g];
    const uint index = dt_as_uint(partials[DT_PARTIAL_ARGMAX * groups + g]);
    if (value > best || (value == best && index < best_index)) {
      best = value;
      best_index = index;
    }
  }
  return dt_group_argmax(scratch, scratch_index, best, best_index, heaviest);
}

/* The rotation mean after `steps` Karcher steps, from the heaviest particle's rotation. */
DT_DEVICE_FN dt_quat dt_partials_mean(DT_LOCAL_PTR float* scratch, __global const float* state,
                                      __global const float* partials, uint groups, uint heaviest, uint steps) {
  dt_quat mean = dt_load_rotation(state, heaviest);
  for (uint s = 0; s < steps; ++s) {
    float step[3];
    for (uint k = 0; k < 3; ++k) step[k] = dt_partials_sum(scratch, partials, DT_PARTIAL_STEP + 3 * s + k, groups);
    mean = dt_quat_normalize(dt_quat_mul(mean, dt_quat_exp(dt_vec3_make(step[0], step[1], step[2]))));
  }
  return mean;
}

__kernel void summarize_max(__global const float* log_weight, __global const float* log_likelihood, uint count,
                            __global float* partials) {
  __local float scratch[DT_GROUP_SIZE];
  __local uint scratch_index[DT_GROUP_SIZE];
  const uint groups = get_num_groups(0), group = get_group_id(0);
  uint heaviest;
  float max_ll;
  const float max_log_weight = dt_group_max_weight(scratch, scratch_index, log_weight, log_likelihood,
                                                   get_global_id(0), get_global_size(0), count, &heaviest, &max_ll);
  if (get_local_id(0) == 0) {
    partials[DT_PARTIAL_MAX * groups + group] = max_log_weight;
    partials[DT_PARTIAL_ARGMAX * groups + group] = dt_as_float(heaviest);
    partials[DT_PARTIAL_MAX_LL * groups + group] = max_ll;
  }
}

__kernel void summarize_sum(__global const float* log_weight, uint count, __global float* partials) {
  __local float scratch[DT_GROUP_SIZE];
  __local uint scratch_index[DT_GROUP_SIZE];
  const uint groups = get_num_groups(0);
  uint heaviest;
  const float max_log_weight = dt_partials_max(scratch, scratch_index, partials, groups, &heaviest);
  float sum = 0.0f;
  for (uint i = get_global_id(0); i < count; i += get_global_size(0)) sum += exp(log_weight[i] - max_log_weight);
  sum = dt_group_sum(scratch, sum);
  if (get_local_id(0) == 0) partials[DT_PARTIAL_SUM * groups + get_group_id(0)] = sum;
}

/* A particle whose weight is exactly 0 adds exactly 0 to every sum (its state is finite): not read. */
__kernel void summarize_weights(__global const float* state, __global const float* log_weight,
                                __global const float* log_likelihood, __global float* weights, uint count,
                                float centre_x, float centre_y, float centre_z, __global float* partials) {
  __local float scratch[DT_GROUP_SIZE];
  __local uint scratch_index[DT_GROUP_SIZE];
  const uint groups = get_num_groups(0);
  const dt_vec3 centre = dt_vec3_make(centre_x, centre_y, centre_z);
  uint heaviest;
  const float max_log_weight = dt_partials_max(scratch, scratch_index, partials, groups, &heaviest);
  const float total = dt_partials_sum(scratch, partials, DT_PARTIAL_SUM, groups);
  float acc[DT_WEIGHTED_SUMS];
  for (int k = 0; k < DT_WEIGHTED_SUMS; ++k) acc[k] = 0.0f;
  for (uint i = get_global_id(0); i < count; i += get_global_size(0)) {
    const float w = exp(log_weight[i] - max_log_weight) / total;
    weights[i] = w;
    if (w > 0.0f) dt_add_weighted(acc, state, log_likelihood, i, w, centre);
  }
  for (int k = 0; k < DT_WEIGHTED_SUMS; ++k) {
    const float sum = dt_group_sum(scratch, acc[k]);
    if (get_local_id(0) == 0) partials[(DT_PARTIAL_ACC + k) * groups + get_group_id(0)] = sum;
  }
}

__kernel void summarize_karcher(__global const float* state, __global const float* weights, uint count, uint iteration,
                                __global float* partials) {
  __local float scratch[DT_GROUP_SIZE];
  __local uint scratch_index[DT_GROUP_SIZE];
  const uint groups = get_num_groups(0);
  uint heaviest;
  dt_partials_max(scratch, scratch_index, partials, groups, &heaviest);
  const dt_quat mean = dt_partials_mean(scratch, state, partials, groups, heaviest, iteration);
  float step[3] = {0.0f, 0.0f, 0.0f};
  for (uint i = get_global_id(0); i < count; i += get_global_size(0))
    if (weights[i] > 0.0f) dt_add_karcher_step(step, state, i, weights[i], mean);
  for (uint k = 0; k < 3; ++k) {
    const float sum = dt_group_sum(scratch, step[k]);
    if (get_local_id(0) == 0) partials[(DT_PARTIAL_STEP + 3 * iteration + k) * groups + get_group_id(0)] = sum;
  }
}

/* One group; groups: how many the passes before ran with. */
__kernel void summarize_finish(__global const float* state, __global float* estimate, uint count, uint groups,
                               float centre_x, float centre_y, float centre_z, float kl_threshold,
                               __global const float* partials, uint karcher_steps) {
  __local float scratch[DT_GROUP_SIZE];
  __local uint scratch_index[DT_GROUP_SIZE];
  const dt_vec3 centre = dt_vec3_make(centre_x, centre_y, centre_z);
  uint heaviest;
  dt_partials_max(scratch, scratch_index, partials, groups, &heaviest);
  float max_ll = DT_LOWEST;
  for (uint g = get_local_id(0); g < groups; g += DT_GROUP_SIZE)
    max_ll = fmax(max_ll, partials[DT_PARTIAL_MAX_LL * groups + g]);
  uint unused;
  max_ll = dt_group_argmax(scratch, scratch_index, max_ll, 0, &unused);
  float acc[DT_WEIGHTED_SUMS];
  for (uint k = 0; k < DT_WEIGHTED_SUMS; ++k) acc[k] = dt_partials_sum(scratch, partials, DT_PARTIAL_ACC + k, groups);
  const dt_quat mean = dt_partials_mean(scratch, state, partials, groups, heaviest, karcher_steps);
  if (get_local_id(0) == 0) dt_write_estimate(estimate, acc, mean, centre, count, max_ll, heaviest, kl_threshold);
}
