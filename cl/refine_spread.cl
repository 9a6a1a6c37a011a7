/* The pose refinement spread over many work-groups: the same fit as cl/refine.cl's one-group kernel
 * (dt_refine.h holds what both share), but every evaluation of a candidate pose is two kernels over
 * the whole device: its triangles drawn, a work-item per triangle (or per slice of a triangle's rows:
 * dt_refine_draw_item), into one 64-bit word per pixel
 * (depth bits and triangle index, kept by atomic min: dt_raster_triangle_rows' `nearest`), then the
 * image's pixels summed into one row of DT_REFINE_SUMS partial sums per work-group. The last group
 * of the sums to finish (a counter in the fit's state) adds the rows in a fixed order (no float
 * atomics: the same sums every run; how it knows the rows are complete: refine_sums), keeps or rejects the candidate,
 * solves the next step and writes the next candidate into the fit's state (dt_refine_state.h). The host enqueues begin,
 * then iterations + 1 evaluations, with no round trip; once the fit has stopped (converged, or no step left to try),
 * `active` is 0 and the later kernels return at once; with a second stage (args.stages 2) the host enqueues
 * twice as many evaluations and the state's `stage` picks each evaluation's sigma(y). The judgement that stops it
 * writes the results, as the one-group kernel does. No pixel box: a work-item per pixel costs nothing more on a GPU
 * than one per box pixel, and the judgement then has no vertex loop. Invariant between evaluations: nearest holds
 * DT_NEAREST_EMPTY at every pixel (the sums kernel resets every pixel it reads), so no kernel clears. Needs 64-bit
 * atomic min (cl_khr_int64_extended_atomics; CUDA has it): without it Auto picks the one-group layout
 * (resolved_refine_layout). Compile-time choices as for refine.cl (DT_GROUP_SIZE: the sums kernel's groups;
 * DT_OCCLUSION). Reference: PoseRefiner::refine and ReferenceFilter::refine. */
#ifdef __OPENCL_VERSION__
#pragma OPENCL EXTENSION cl_khr_int64_extended_atomics : enable
#endif
#define DT_NEAREST_PACKED 1
#include "dt_refine.h"
#include "dt_summarize.h"
#if DT_WEIGHTED_SUMS > DT_REFINE_SUMS
#error "refine_one_launch's summary sums in the fit's scratch"
#endif

/* The fit's state at the frame's start: the start (the heaviest particle, which summarize found) is the
 * first candidate. */
DT_DEVICE_FN void dt_refine_start(__global dt_refine_state* s, __global const float* estimate,
                                  __global const float* states, dt_refine_args args, dt_window win) {
  s->args = args;
  s->win = win;
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  dt_store_pose(s->candidate, dt_load_pose(states + DT_CAST(ulong, heaviest) * DT_STATE_STRIDE));
  s->active = 1;
  s->stage = 0;
  s->evaluation = 0;
  s->arrived = 0;
  s->tried = 0;
  s->lambda = args.damping;
}

/* One work-item: dt_refine_start. */
__kernel void refine_begin(__global dt_refine_state* s, __global const float* estimate, __global const float* states,
                           dt_refine_args args, dt_window win) {
  if (get_global_id(0) == 0) dt_refine_start(s, estimate, states, args, win);
}

#define DT_REFINE_MAX_POLLS (1u << 20)

/* The candidate's depth and each pixel's triangle, in one pass: a work-item per triangle and slice of its
 * rows (dt_refine_draw_item). */
__kernel void refine_draw(__global const dt_refine_state* s, __global const float* vertices,
                          __global const uint* triangles, __global const float* planes, uint triangle_count,
                          dt_camera cam, __global dt_u64* nearest) {
  if (!s->active) return;
  const uint item = get_global_id(0);
  if (item < triangle_count * s->args.draw_slices)
    dt_refine_draw_item(dt_particle_pose(s->candidate), vertices, triangles, planes, triangle_count,
                        s->args.draw_slices, item, cam, 0, 0, nearest);
}

/* One work-item of the last group, with the candidate's sums: PoseRefiner's loop body. Keeps or
 * rejects the candidate (a stage's start is kept) and, unless this was the stage's last evaluation,
 * solves the next step from the best pose and makes it the candidate. With no next candidate the next
 * stage (args.stages 2) starts from the best pose, or, after the last stage, the fit ends here:
 * results into estimate and correction (as refine.cl). */
DT_DEVICE_FN void dt_refine_judge(__global dt_refine_state* s, __global float* estimate, __global const float* states,
                                  const float* sums, dt_refine_args args, __global float* correction) {
  const dt_vec3 centre = dt_vec3_make(args.centre_x, args.centre_y, args.centre_z);
  float lambda = s->lambda;
  const float tolerance = dt_refine_stage_args(args, s->stage).step_tolerance; /* the judged evaluation's stage */
  if (s->evaluation == 0 || dt_refine_keeps(sums[DT_REFINE_OBJECTIVE], s->best_sums[DT_REFINE_OBJECTIVE], tolerance)) {
    for (int k = 0; k < DT_REFINE_SUMS; ++k) s->best_sums[k] = sums[k];
    for (int k = 0; k < DT_STATE_STRIDE; ++k) s->best[k] = s->candidate[k];
    lambda = args.damping;
  } else {
    lambda = dt_refine_damping_after_rejection(lambda);
  }
  float best_sums[DT_REFINE_SUMS];
  for (int k = 0; k < DT_REFINE_SUMS; ++k) best_sums[k] = s->best_sums[k];
  const dt_pose best = dt_load_pose(s->best);
  float step[6];
  const int proceed = DT_CAST(int, s->evaluation) < args.iterations && dt_refine_step(best_sums, lambda, args, step);
  s->evaluation += 1;
  s->lambda = lambda;
  if (proceed) {
    dt_store_pose(s->candidate, dt_apply_twist(best, centre, step));
    s->tried += 1;
    return;
  }
  if (s->stage + 1 < args.stages) { /* the next stage: the best pose is its start, judged afresh */
    s->stage += 1;
    s->evaluation = 0;
    for (int k = 0; k < DT_STATE_STRIDE; ++k) s->candidate[k] = s->best[k];
    return;
  }
  s->active = 0;
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  const dt_pose start = dt_load_pose(states + DT_CAST(ulong, heaviest) * DT_STATE_STRIDE);
  dt_refine_finish(estimate, start, best, best_sums, s->tried, centre, correction);
}

/* The normal equations' sums of the pixels first, first + stride, ... that the candidate drew, into
 * acc (DT_REFINE_SUMS, zeroed here), each pixel read reset for the next evaluation: refine_sums strides
 * over the grid, refine_one_launch over its one group. */
DT_DEVICE_FN void dt_refine_sum_drawn(float* acc, uint first, uint stride, __global dt_u64* nearest, dt_rigid pose,
                                      dt_refine_args args, __global const float* observed,
                                      __global const float* occlusion, __global const dt_u16* occlusion_time,
                                      __global const float* frame_times, dt_refine_offsets at,
                                      __global const float* planes, uint triangle_count, dt_camera cam, dt_model m) {
  const dt_vec3 centre = dt_vertex_at(pose, args.centre_x, args.centre_y, args.centre_z);
  for (int k = 0; k < DT_REFINE_SUMS; ++k) acc[k] = 0.0f;
  for (uint k = first; k < cam.width * cam.height; k += stride) {
    const dt_u64 drawn = nearest[k];
    if (drawn == DT_NEAREST_EMPTY) continue; /* nothing drawn: nothing to reset or sum */
    nearest[k] = DT_NEAREST_EMPTY;
    dt_refine_pixel(acc, k, DT_CAST(uint, drawn >> 32), DT_CAST(uint, drawn & 0xffffffffu), pose, centre, observed,
                    occlusion, occlusion_time, frame_times, at, planes, triangle_count, cam, m, args);
  }
}

/* Sum k's partials added in group order into *total; 1 if every word carried this evaluation's stamp.
 * Eight words' loads at a time, before any is looked at, so that they are in flight together. */
#define DT_REFINE_WORDS_AT_ONCE 8
DT_DEVICE_FN int dt_refine_add_column(__global volatile const dt_u64* rows, uint groups, uint k, uint stamp,
                                      float* total) {
  float sum = 0.0f;
  uint stale = 0;
  for (uint g0 = 0; g0 < groups; g0 += DT_REFINE_WORDS_AT_ONCE) {
    dt_u64 word[DT_REFINE_WORDS_AT_ONCE];
    for (uint i = 0; i < DT_REFINE_WORDS_AT_ONCE; ++i)
      word[i] = g0 + i < groups ? rows[DT_CAST(ulong, g0 + i) * DT_REFINE_SUMS + k] : DT_CAST(dt_u64, stamp) << 32;
    for (uint i = 0; i < DT_REFINE_WORDS_AT_ONCE; ++i) {
      stale |= DT_CAST(uint, word[i] >> 32) ^ stamp;
      sum += dt_as_float(DT_CAST(uint, word[i] & 0xffffffffu)); /* past the groups: + 0 */
    }
  }
  *total = sum;
  return stale == 0;
}

/* The image's pixels over all work-items of the grid; each group's sums into its row of partials,
 * every pixel read reset for the next evaluation. The last group to count itself in then adds the
 * rows in group order, a work-item per sum, and its work-item 0 judges (dt_refine_judge). The other groups have read
 * the fit's state before they count themselves in, so the last one may write it. No fence is needed for the rows:
 * OpenCL 1.2 has none that reaches other work-groups (NVIDIA's mem_fence is membar.cta), so each partial is stored with
 * the evaluation's stamp in one 64-bit word, (stamp << 32) | bits, and the last group waits for every word to carry
 * this evaluation's stamp: the other groups have finished, only their stores can still be on the way. */
__kernel void refine_sums(__global dt_refine_state* s, __global float* estimate, __global const float* states,
                          __global const float* observed, __global const float* occlusion,
                          __global const dt_u16* occlusion_time, __global const float* frame_times,
                          __global const uint* parents, __global const float* planes, uint triangle_count,
                          dt_camera cam, dt_model m, __global dt_u64* nearest, __global dt_u64* partials,
                          __global float* correction) {
  __local float sums[DT_REFINE_SCRATCH];
  __local int last, lost;
  if (!s->active) return; /* the same for every work-item, before any barrier */
  const uint stamp = s->stamp;
  const dt_refine_args args = s->args;
  const dt_window win = s->win;
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  const dt_refine_offsets at = dt_refine_map_offsets(parents[heaviest], win);
  const dt_rigid pose = dt_particle_pose(s->candidate);
  const uint stage = s->stage;
  float acc[DT_REFINE_SUMS];
  dt_refine_sum_drawn(acc, get_global_id(0), get_global_size(0), nearest, pose, dt_refine_stage_args(args, stage),
                      observed, occlusion, occlusion_time, frame_times, at, planes, triangle_count, cam,
                      dt_refine_stage_model(m, args, stage));
  dt_group_sums(acc, DT_REFINE_SUMS, sums);
  const uint lid = get_local_id(0), groups = get_num_groups(0);
  if (lid < DT_REFINE_SUMS)
    partials[DT_CAST(ulong, get_group_id(0)) * DT_REFINE_SUMS + lid] =
        (DT_CAST(dt_u64, stamp) << 32) | dt_as_uint(sums[lid]);
  barrier(CLK_GLOBAL_MEM_FENCE); /* the row's stores issued before the group counts itself in */
  /* Work-item 0 counts the group in; the whole group learns whether it came last. Every group passes
   * every barrier (none is behind a return or a branch: PoCL ran every work-item of a group through a
   * return placed before a barrier). */
  if (lid == 0) {
    last = dt_atomic_add_u32(&s->arrived, 1u) == groups - 1;
    lost = 0;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  /* In the last group, work-item k adds sum k over the groups' rows (volatile: read again, not from a
   * cache). Nearly always every word already carries the stamp; only if one does not is sum k's
   * column polled, word by word, and added again (the same sums, in the same order). */
  if (last && lid < DT_REFINE_SUMS) {
    __global volatile const dt_u64* rows = partials;
    float total;
    if (!dt_refine_add_column(rows, groups, lid, stamp, &total)) {
      for (uint g = 0; g < groups; ++g) {
        const ulong at_row = DT_CAST(ulong, g) * DT_REFINE_SUMS + lid;
        dt_u64 word = rows[at_row];
        /* A bound, so that a fault can never hang the device: past it the evaluation counts as lost. */
        for (uint polls = 0; DT_CAST(uint, word >> 32) != stamp && polls < DT_REFINE_MAX_POLLS; ++polls)
          word = rows[at_row];
      }
      if (!dt_refine_add_column(rows, groups, lid, stamp, &total)) lost = 1; /* any of them: the same 1 */
    }
    sums[lid] = total;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (!last || lid != 0) return;
  float total[DT_REFINE_SUMS];
  for (int k = 0; k < DT_REFINE_SUMS; ++k) total[k] = sums[k];
  s->arrived = 0;
  s->stamp = stamp + 1;
  /* A lost evaluation counts as a rejected candidate (the start as one without pixels: the fit ends there). */
  if (lost) total[DT_REFINE_PIXELS] = 0.0f, total[DT_REFINE_OBJECTIVE] = DT_LOWEST;
  dt_refine_judge(s, estimate, states, total, args, correction);
}

/* The whole fit in one work-group and one launch (the one-launch layout): the start, then each
 * evaluation's draw and sums as above, with the group's barriers where the spread layout has kernel
 * boundaries, and work-item 0 judging; it stops as soon as the fit does. One launch a frame instead of
 * 2 x (iterations + 1) + 1: on a driver whose launches cost the host several microseconds each (NVIDIA's
 * OpenCL) that outweighs spreading the draws and sums over the device. With summarize, the group first
 * does summarize.cl's work (dt_summarize.h; the fit starts from the heaviest particle it finds), so a
 * small cloud's summary and fit take one launch; its rotation mean is not iterated (the fit replaces
 * the mean pose), and its sums run over this program's DT_GROUP_SIZE work-items, not summarize.cl's
 * group: the same terms added in another order. Without it (a cloud summarized over many groups
 * before) the summary's arguments are not read. Then the arguments of refine_begin and refine_sums. */
__kernel void refine_one_launch(__global const float* log_weight, __global const float* log_likelihood,
                                __global float* weights, uint count, float centre_x, float centre_y, float centre_z,
                                float kl_threshold, uint summarize, __global dt_refine_state* s,
                                __global float* estimate, __global const float* states, __global const float* observed,
                                __global const float* occlusion, __global const dt_u16* occlusion_time,
                                __global const float* frame_times, __global const uint* parents,
                                __global const float* vertices, __global const uint* triangles,
                                __global const float* planes, uint triangle_count, dt_camera cam, dt_model m,
                                dt_refine_args args, dt_window win, __global dt_u64* nearest,
                                __global float* correction) {
  __local float scratch[DT_GROUP_SIZE];
  __local uint scratch_index[DT_GROUP_SIZE];
  __local float sums[DT_REFINE_SCRATCH]; /* the summary's DT_GROUP_SUMS_SCRATCH(DT_WEIGHTED_SUMS), then the fit's */
  __local int active;
  const uint lid = get_local_id(0);
  if (summarize) { /* a kernel argument: every work-item meets the summary's barriers */
    dt_summarize(states, log_weight, log_likelihood, weights, estimate, count,
                 dt_vec3_make(centre_x, centre_y, centre_z), kl_threshold, 0u, scratch, scratch_index, sums);
    barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE); /* the estimate and weights written; sums free */
  }
  if (lid == 0) dt_refine_start(s, estimate, states, args, win);
  barrier(CLK_GLOBAL_MEM_FENCE);
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  const dt_refine_offsets at = dt_refine_map_offsets(parents[heaviest], win);
  for (;;) {
    const dt_rigid pose = dt_particle_pose(s->candidate);
    for (uint item = lid; item < triangle_count * args.draw_slices; item += DT_GROUP_SIZE)
      dt_refine_draw_item(pose, vertices, triangles, planes, triangle_count, args.draw_slices, item, cam, 0, 0,
                          nearest);
    barrier(CLK_GLOBAL_MEM_FENCE);
    const uint stage = s->stage;
    float acc[DT_REFINE_SUMS];
    dt_refine_sum_drawn(acc, lid, DT_GROUP_SIZE, nearest, pose, dt_refine_stage_args(args, stage), observed, occlusion,
                        occlusion_time, frame_times, at, planes, triangle_count, cam,
                        dt_refine_stage_model(m, args, stage));
    dt_group_sums(acc, DT_REFINE_SUMS, sums);
    if (lid == 0) {
      float total[DT_REFINE_SUMS];
      for (int k = 0; k < DT_REFINE_SUMS; ++k) total[k] = sums[k];
      dt_refine_judge(s, estimate, states, total, args, correction);
      active = DT_CAST(int, s->active);
    }
    /* The next candidate (global) and the decision (local) seen by the whole group; every work-item
     * has read this evaluation's sums and reset its pixels. */
    barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
    if (!active) break;
  }
}
