/* Normalization, degeneracy and the estimate, in one work-group of DT_GROUP_SIZE that strides over
 * all particles: log-sum-exp, ESS, KL from uniform, the weighted mean centre and velocities, and the
 * rotation mean in the tangent space of the heaviest particle (karcher_steps Karcher iterations: 0
 * when the refinement replaces the mean pose, which then stays the heaviest particle's rotation), and the
 * resampling decision (KL > kl_threshold) that resample.cl's kernels read. With the effective sample
 * size near 1 nearly every weight is exactly 0 in float, and such a particle adds exactly 0 to every
 * weighted sum (its state is finite), so its state is not read: the passes over the states then cost
 * a read of the weights (one group strides over all particles: at a million particles each state read
 * was a wait on memory).
 * Reference: summarize_log_weights and weighted_mean_pose. */
#include "dt_summarize.h"

__kernel void summarize(__global const float* state, __global const float* log_weight,
                        __global const float* log_likelihood, __global float* weights, __global float* estimate,
                        uint count, float centre_x, float centre_y, float centre_z, float kl_threshold,
                        uint karcher_steps) {
  __local float scratch[DT_GROUP_SIZE];
  __local uint scratch_index[DT_GROUP_SIZE];
  __local float sums[DT_GROUP_SUMS_SCRATCH(DT_WEIGHTED_SUMS)];
  dt_summarize(state, log_weight, log_likelihood, weights, estimate, count, dt_vec3_make(centre_x, centre_y, centre_z),
               kl_threshold, karcher_steps, scratch, scratch_index, sums);
}
