/* Systematic resampling on the device: prefix sum of the normalized weights, then each child's parent
 * by binary search and the gather of its kinematic state, with the refinement's shift, in one kernel
 * (resample_particles; for small clouds resample_scanning does the prefix sum too). Their per-pixel occlusion
 * state is not copied here: the next frame's weigh reads each child's row from its parent
 * (weigh.cl), so parents always holds the last frame's choice (the identity without resampling).
 * Reference: systematic_resample.
 * Whether to resample is decided on the device too: summarize.cl sets estimate[DT_EST_RESAMPLE],
 * and every kernel here that takes `estimate` reads it, so that the host enqueues the same
 * sequence each frame without waiting for the decision: without it they return at once, but
 * resample_particles writes the identity and copies (the host swaps the state buffers every frame). */
#include "dt_prelude.h"
#include "dt_pose_twist.h"
#include "dt_state.h"

DT_DEVICE_FN int dt_resampling(__global const float* estimate) {
  return estimate[DT_EST_RESAMPLE] != 0.0f;
}

/* Float-float arithmetic: a value is hi + lo with |lo| <= ulp(hi) / 2, about 48 bits, so the
 * cumulative weights and the comparisons against them round like the reference's doubles. */
DT_DEVICE_FN void dt_two_sum(float a, float b, float* hi, float* lo) {
  const float s = a + b;
  const float bb = s - a;
  *hi = s;
  *lo = (a - (s - bb)) + (b - bb);
}
DT_DEVICE_FN void dt_ff_add(float* hi, float* lo, float value) {
  float s, e;
  dt_two_sum(*hi, value, &s, &e);
  e += *lo;
  dt_two_sum(s, e, hi, lo);
}

/* The float-float sum of values [begin, end), added in order. */
DT_DEVICE_FN void dt_ff_sum(__global const float* values, uint begin, uint end, float* hi, float* lo) {
  *hi = 0.0f;
  *lo = 0.0f;
  for (uint i = begin; i < end; ++i) dt_ff_add(hi, lo, values[i]);
}

/* Values [begin, end) cut into one contiguous sub-chunk per work-item, [*from, *to): each work-item's
 * float-float sum of its sub-chunk goes to part_hi, part_lo[lid]; on return every work-item sees all. */
DT_DEVICE_FN void dt_sub_chunk_sums(__global const float* values, uint begin, uint end, DT_LOCAL_PTR float* part_hi,
                                    DT_LOCAL_PTR float* part_lo, uint* from, uint* to) {
  const uint lid = get_local_id(0);
  const uint chunk = (end - begin + DT_GROUP_SIZE - 1) / DT_GROUP_SIZE;
  *from = min(end, begin + lid * chunk);
  *to = min(end, *from + chunk);
  float hi, lo;
  dt_ff_sum(values, *from, *to, &hi, &lo);
  part_hi[lid] = hi;
  part_lo[lid] = lo;
  barrier(CLK_LOCAL_MEM_FENCE);
}

/* The float-float sum of the group's DT_GROUP_SIZE pairs, in order (work-item 0 calls it). */
DT_DEVICE_FN void dt_pairs_total(DT_LOCAL_PTR const float* part_hi, DT_LOCAL_PTR const float* part_lo, float* hi,
                                 float* lo) {
  *hi = 0.0f;
  *lo = 0.0f;
  for (uint g = 0; g < DT_GROUP_SIZE; ++g) {
    dt_ff_add(hi, lo, part_hi[g]);
    dt_ff_add(hi, lo, part_lo[g]);
  }
}

/* The sub-chunk totals in part_hi, part_lo made each sub-chunk's running sum before it, from
 * (start_hi, start_lo), by work-item 0 in order; on return every work-item sees all. */
DT_DEVICE_FN void dt_chunk_starts(DT_LOCAL_PTR float* part_hi, DT_LOCAL_PTR float* part_lo, float start_hi,
                                  float start_lo) {
  if (get_local_id(0) == 0) {
    float run_hi = start_hi, run_lo = start_lo;
    for (uint g = 0; g < DT_GROUP_SIZE; ++g) {
      const float chunk_hi = part_hi[g], chunk_lo = part_lo[g];
      part_hi[g] = run_hi;
      part_lo[g] = run_lo;
      dt_ff_add(&run_hi, &run_lo, chunk_hi);
      dt_ff_add(&run_hi, &run_lo, chunk_lo);
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);
}

/* Inclusive prefix sum of values [begin, end) in one work-group, starting from (hi, lo) before begin,
 * as float-float pairs written to cumulative[2i], cumulative[2i+1]: each work-item sums a contiguous
 * sub-chunk, work-item 0 scans the sub-chunk totals, then each writes its sub-chunk's running sums. */
DT_DEVICE_FN void dt_scan_range(__global const float* values, __global float* cumulative, uint begin, uint end,
                                float start_hi, float start_lo, DT_LOCAL_PTR float* part_hi,
                                DT_LOCAL_PTR float* part_lo) {
  const uint lid = get_local_id(0);
  uint from, to;
  dt_sub_chunk_sums(values, begin, end, part_hi, part_lo, &from, &to);
  dt_chunk_starts(part_hi, part_lo, start_hi, start_lo);
  float hi = part_hi[lid], lo = part_lo[lid];
  for (uint i = from; i < to; ++i) {
    dt_ff_add(&hi, &lo, values[i]);
    cumulative[2 * i] = hi;
    cumulative[2 * i + 1] = lo;
  }
}

/* Inclusive prefix sum over count values in one work-group (small clouds). */
__kernel void prefix_sum(__global const float* values, __global float* cumulative, uint count,
                         __global const float* estimate) {
  __local float part_hi[DT_GROUP_SIZE];
  __local float part_lo[DT_GROUP_SIZE];
  if (!dt_resampling(estimate)) return; /* the same for the whole group: no barrier is split */
  dt_scan_range(values, cumulative, 0, count, 0.0f, 0.0f, part_hi, part_lo);
}

/* The same over many groups (large clouds), two launches: group g takes the g-th of get_num_groups
 * contiguous ranges; prefix_sum_totals leaves each range's float-float total in totals[2g, 2g+1],
 * prefix_sum_ranges scans each range from the sum of the totals before it. */
DT_DEVICE_FN uint dt_range_begin(uint count, uint group, uint groups) {
  const uint length = (count + groups - 1) / groups;
  return min(count, group * length);
}

__kernel void prefix_sum_totals(__global const float* values, uint count, __global float* totals,
                                __global const float* estimate) {
  __local float part_hi[DT_GROUP_SIZE];
  __local float part_lo[DT_GROUP_SIZE];
  if (!dt_resampling(estimate)) return;
  const uint group = get_group_id(0), groups = get_num_groups(0);
  uint from, to;
  dt_sub_chunk_sums(values, dt_range_begin(count, group, groups), dt_range_begin(count, group + 1, groups), part_hi,
                    part_lo, &from, &to);
  if (get_local_id(0) == 0) {
    float hi, lo;
    dt_pairs_total(part_hi, part_lo, &hi, &lo);
    totals[2 * group] = hi;
    totals[2 * group + 1] = lo;
  }
}

__kernel void prefix_sum_ranges(__global const float* values, __global float* cumulative, uint count,
                                __global const float* totals, __global const float* estimate) {
  __local float part_hi[DT_GROUP_SIZE];
  __local float part_lo[DT_GROUP_SIZE];
  __local float start[2];
  if (!dt_resampling(estimate)) return;
  const uint group = get_group_id(0), groups = get_num_groups(0), lid = get_local_id(0);
  /* The totals of the ranges before this one: each work-item adds every DT_GROUP_SIZE-th, work-item 0
   * adds those sums in order (the same order in every run). */
  float hi = 0.0f, lo = 0.0f;
  for (uint g = lid; g < group; g += DT_GROUP_SIZE) {
    dt_ff_add(&hi, &lo, totals[2 * g]);
    dt_ff_add(&hi, &lo, totals[2 * g + 1]);
  }
  part_hi[lid] = hi;
  part_lo[lid] = lo;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lid == 0) {
    dt_pairs_total(part_hi, part_lo, &hi, &lo);
    start[0] = hi;
    start[1] = lo;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  const float start_hi = start[0], start_lo = start[1];
  barrier(CLK_LOCAL_MEM_FENCE); /* part_hi and part_lo are used again */
  dt_scan_range(values, cumulative, dt_range_begin(count, group, groups), dt_range_begin(count, group + 1, groups),
                start_hi, start_lo, part_hi, part_lo);
}

/* Does cumulative weight (hi + lo) exceed (u + child) / count? Compared as
 * (hi + lo) * count > u + child without dividing, products split exactly with fma. */
DT_DEVICE_FN int dt_exceeds(float hi, float lo, float count, float u, float child) {
  const float p = hi * count;
  const float p_err = fma(hi, count, -p) + lo * count;
  float s, s_err;
  dt_two_sum(child, u, &s, &s_err);
  return (p - s) + (p_err - s_err) > 0.0f;
}

/* The first parent whose cumulative weight exceeds (u + child) / count (the last if none). */
DT_DEVICE_FN uint dt_find_parent(__global const float* cumulative, uint count, float u, uint child) {
  uint lo = 0, hi = count - 1; /* the answer lies in [lo, hi] */
  while (lo < hi) {
    const uint mid = lo + (hi - lo) / 2;
    if (dt_exceeds(cumulative[2 * mid], cumulative[2 * mid + 1], DT_CAST(float, count), u, DT_CAST(float, child)))
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

/* The first parent whose cumulative weight exceeds (u + child) / count (the last if none), where the
 * cumulative weights are not stored but each of the group's sub-chunks has its start and its last
 * cumulative weight in work-group memory (resample_scanning): the first sub-chunk whose last weight
 * exceeds, then a walk through it from its start. The walk adds what dt_scan_range adds, in its order,
 * so the values compared, and (the weights being non-negative, the sums non-decreasing) the parent,
 * are dt_find_parent's over prefix_sum's output. */
DT_DEVICE_FN uint dt_find_parent_in_chunks(__global const float* values, uint count, float u, uint child,
                                           DT_LOCAL_PTR const float* start_hi, DT_LOCAL_PTR const float* start_lo,
                                           DT_LOCAL_PTR const float* last_hi, DT_LOCAL_PTR const float* last_lo) {
  const uint chunk = (count + DT_GROUP_SIZE - 1) / DT_GROUP_SIZE;
  uint lo = 0, hi = (count + chunk - 1) / chunk - 1; /* the non-empty sub-chunks */
  while (lo < hi) {
    const uint mid = lo + (hi - lo) / 2;
    if (dt_exceeds(last_hi[mid], last_lo[mid], DT_CAST(float, count), u, DT_CAST(float, child)))
      hi = mid;
    else
      lo = mid + 1;
  }
  float sum_hi = start_hi[lo], sum_lo = start_lo[lo];
  const uint end = min(count, (lo + 1) * chunk);
  for (uint i = lo * chunk; i < end; ++i) {
    dt_ff_add(&sum_hi, &sum_lo, values[i]);
    if (dt_exceeds(sum_hi, sum_lo, DT_CAST(float, count), u, DT_CAST(float, child))) return i;
  }
  return count - 1;
}

/* Child j of parent: parents[j], the parent's kinematic state copied from `from` into `to`, moved
 * with shift by the correction twist about the centre (velocities unchanged: the cloud follows the
 * refined pose); after a resampling the log weight starts afresh at 0. */
DT_DEVICE_FN void dt_resample_child(uint child, uint parent, int resampling, __global uint* parents,
                                    __global const float* from, __global float* to, __global float* log_weight,
                                    __global const float* correction, dt_vec3 centre, uint shift) {
  parents[child] = parent;
  if (resampling) log_weight[child] = 0.0f;
  __global const float* source = from + DT_CAST(ulong, parent) * DT_STATE_STRIDE;
  __global float* target = to + DT_CAST(ulong, child) * DT_STATE_STRIDE;
  for (int k = 0; k < DT_STATE_STRIDE; ++k) target[k] = source[k];
  if (!shift) return;
  const float twist[6] = {correction[0], correction[1], correction[2], correction[3], correction[4], correction[5]};
  dt_store_pose(target, dt_apply_twist(dt_load_pose(source), centre, twist));
}

/* The frame's resampling and the cloud's shift, a work-item per child (one launch for what were three:
 * find the parents, gather their states, move them): child j takes its parent (dt_find_parent; without
 * resampling each particle is its own), writes it to parents (the next weigh reads the child's occlusion
 * row from there), copies the parent's kinematic state from `from` into `to` and, with shift, moves its
 * pose by the refinement's correction twist about the mesh's centre (velocities unchanged: the cloud
 * follows the refined pose). After a resampling the log weights start afresh at 0. Reference:
 * systematic_resample, then ReferenceFilter::refine's shift. */
__kernel void resample_particles(__global const float* cumulative, __global uint* parents, uint count, float u,
                                 __global const float* estimate, __global const float* from, __global float* to,
                                 __global float* log_weight, __global const float* correction, float centre_x,
                                 float centre_y, float centre_z, uint shift) {
  const uint child = get_global_id(0);
  if (child >= count) return;
  const int resampling = dt_resampling(estimate);
  dt_resample_child(child, resampling ? dt_find_parent(cumulative, count, u, child) : child, resampling, parents,
                    from, to, log_weight, correction, dt_vec3_make(centre_x, centre_y, centre_z), shift);
}

/* resample_particles for a cloud small enough (the host's kFusedLaunchParticles) that every
 * group of DT_GROUP_SIZE scans the weights itself: each group sums and scans their sub-chunks in
 * work-group memory (prefix_sum's first half), and each work-item walks its own sub-chunk from its
 * start to its last cumulative weight (prefix_sum's second half, not stored). The same parents as
 * prefix_sum + resample_particles, one launch and the cumulative weights' round trip fewer; each group
 * repeats the scan, which the GPU runs side by side. The scan runs whether or not the estimate says
 * to resample (a barrier a value in memory decides on is not portable); its cost is a read of the
 * weights. */
__kernel void resample_scanning(__global const float* weights, __global uint* parents, uint count, float u,
                                __global const float* estimate, __global const float* from, __global float* to,
                                __global float* log_weight, __global const float* correction, float centre_x,
                                float centre_y, float centre_z, uint shift) {
  __local float start_hi[DT_GROUP_SIZE];
  __local float start_lo[DT_GROUP_SIZE];
  __local float last_hi[DT_GROUP_SIZE];
  __local float last_lo[DT_GROUP_SIZE];
  const uint lid = get_local_id(0);
  uint first, end;
  dt_sub_chunk_sums(weights, 0, count, start_hi, start_lo, &first, &end);
  dt_chunk_starts(start_hi, start_lo, 0.0f, 0.0f);
  float hi = start_hi[lid], lo = start_lo[lid];
  for (uint i = first; i < end; ++i) dt_ff_add(&hi, &lo, weights[i]);
  last_hi[lid] = hi;
  last_lo[lid] = lo;
  barrier(CLK_LOCAL_MEM_FENCE);
  const uint child = get_global_id(0);
  if (child >= count) return;
  const int resampling = dt_resampling(estimate);
  const uint parent =
      resampling ? dt_find_parent_in_chunks(weights, count, u, child, start_hi, start_lo, last_hi, last_lo) : child;
  dt_resample_child(child, parent, resampling, parents, from, to, log_weight, correction,
                    dt_vec3_make(centre_x, centre_y, centre_z), shift);
}

/* A new particle count between frames (the host drew each child's particle, choice[child], as the
 * reference's set_particle_count does): the child's kinematic state copied from `from` into `to`. */
__kernel void gather_states(__global const uint* choice, uint count, __global const float* from,
                            __global float* to) {
  const uint child = get_global_id(0);
  if (child >= count) return;
  __global const float* source = from + DT_CAST(ulong, choice[child]) * DT_STATE_STRIDE;
  __global float* target = to + DT_CAST(ulong, child) * DT_STATE_STRIDE;
  for (int k = 0; k < DT_STATE_STRIDE; ++k) target[k] = source[k];
}

/* Each particle its own parent: the start, and a state set from the host. */
__kernel void identity_parents(__global uint* parents, uint count) {
  const uint i = get_global_id(0);
  if (i < count) parents[i] = i;
}

__kernel void fill(__global float* values, uint count, float value) {
  const uint i = get_global_id(0);
  if (i < count) values[i] = value;
}

#include "time_index.cl"
