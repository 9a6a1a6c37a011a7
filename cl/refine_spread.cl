/* The pose refinement spread over many work-groups: the same fit as cl/refine.cl's one-group kernel
 * (dt_refine.h holds what both share), but every evaluation of a candidate pose is three kernels over
 * the whole device (its triangles drawn with atomic-min depth, a work-item per triangle; drawn again
 * for each pixel's triangle; the image's pixels summed into one row of DT_REFINE_SUMS partial sums
 * per work-group), and a small kernel adds the partial rows in a fixed order (no float atomics: the
 * same sums every run), keeps or rejects the candidate, solves the next step and writes the next
 * candidate into the fit's state (dt_refine_state.h). The host enqueues begin, then iterations + 1
 * evaluations and steps, with no round trip; once the fit has stopped (converged, or no step left to
 * try), `active` is 0 and the later kernels return at once. The step that stops it writes the
 * results, as the one-group kernel does. No pixel box: a work-item per pixel costs nothing more on a
 * GPU than one per box pixel, and the step kernel then has no vertex loop.
 * Invariant between evaluations: tile holds DT_NO_SURFACE and ids 0xffffffff at every pixel (the sums
 * kernel resets every pixel it reads), so no kernel clears.
 * Compile-time choices as for refine.cl (DT_GROUP_SIZE: the sums kernel's groups; DT_OCCLUSION).
 * Reference: PoseRefiner::refine and ReferenceFilter::refine. */
#include "dt_refine.h"
#include "shift_particles.cl"

/* One work-item: the start (the heaviest particle, which summarize found) is the first candidate. */
__kernel void refine_begin(__global dt_refine_state* s, __global const float* estimate, __global const float* states,
                           float damping) {
  if (get_global_id(0) != 0) return;
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  dt_store_pose(s->candidate, dt_load_pose(states + DT_CAST(ulong, heaviest) * DT_STATE_STRIDE));
  s->active = 1;
  s->evaluation = 0;
  s->tried = 0;
  s->lambda = damping;
}

/* A work-item per triangle: the candidate's depth (ids 0) or, over the finished depth, each pixel's
 * triangle (dt_raster_triangle's second pass). */
DT_DEVICE_FN void dt_refine_draw(__global const dt_refine_state* s, __global const float* vertices,
                                 __global const uint* triangles, __global const float* planes, uint triangle_count,
                                 dt_camera cam, __global uint* tile, __global uint* ids) {
  const uint t = get_global_id(0);
  if (!s->active || t >= triangle_count) return;
  dt_draw_triangle(dt_particle_pose(s->candidate), vertices, triangles, planes, t, cam, tile, ids);
}

__kernel void refine_depth(__global const dt_refine_state* s, __global const float* vertices,
                           __global const uint* triangles, __global const float* planes, uint triangle_count,
                           dt_camera cam, __global uint* tile) {
  dt_refine_draw(s, vertices, triangles, planes, triangle_count, cam, tile, 0);
}

__kernel void refine_ids(__global const dt_refine_state* s, __global const float* vertices,
                         __global const uint* triangles, __global const float* planes, uint triangle_count,
                         dt_camera cam, __global uint* tile, __global uint* ids) {
  dt_refine_draw(s, vertices, triangles, planes, triangle_count, cam, tile, ids);
}

/* The image's pixels over all work-items of the grid; each group's sums into
 * partials[group * DT_REFINE_SUMS + k]. Every pixel read is reset for the next evaluation. */
__kernel void refine_sums(__global const dt_refine_state* s, __global const float* estimate,
                          __global const float* observed, __global const float* occlusion,
                          __global const float* occlusion_time, __global const float* prior,
                          __global const float* atlas, dt_atlas_layout layout, __global const float* planes,
                          uint triangle_count, dt_camera cam, dt_model m, dt_refine_args args, __global uint* tile,
                          __global uint* ids, __global float* partials) {
  __local float sums[DT_REFINE_SUMS * DT_GROUP_SIZE];
  if (!s->active) return; /* the same for every work-item, before any barrier */
  const uint pixels = cam.width * cam.height;
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  const dt_refine_offsets at = dt_refine_map_offsets(heaviest, pixels);
  const ulong heaviest_tile = dt_atlas_tile_start(layout, heaviest);
  const dt_rigid pose = dt_particle_pose(s->candidate);
  const dt_vec3 centre = dt_vertex_at(pose, args.centre_x, args.centre_y, args.centre_z);
  float acc[DT_REFINE_SUMS];
  for (int k = 0; k < DT_REFINE_SUMS; ++k) acc[k] = 0.0f;
  for (uint k = get_global_id(0); k < pixels; k += get_global_size(0)) {
    const uint bits = tile[k], id = ids[k];
    if (bits == DT_NO_SURFACE) continue; /* nothing drawn: nothing to reset or sum */
    tile[k] = DT_NO_SURFACE;
    ids[k] = 0xffffffffu;
    dt_refine_pixel(acc, k, bits, id, pose, centre, observed, occlusion, occlusion_time, prior, at, atlas, layout,
                    heaviest_tile, planes, triangle_count, cam, m, args);
  }
  dt_refine_group_sums(acc, sums);
  const uint lid = get_local_id(0);
  if (lid < DT_REFINE_SUMS)
    partials[DT_CAST(ulong, get_group_id(0)) * DT_REFINE_SUMS + lid] = sums[lid * DT_GROUP_SIZE];
}

/* DT_REFINE_SUMS work-items or more, one group: the candidate's sums, work-item k adding sum k of the
 * group_count partial rows in order; then, on work-item 0, PoseRefiner's loop body: keep or reject
 * the candidate (the start is kept) and, unless this was the last evaluation, solve the next step
 * from the best pose and make it the candidate. With no next candidate the fit ends here: results
 * into estimate and correction (as refine.cl). */
__kernel void refine_step(__global dt_refine_state* s, __global float* estimate, __global const float* states,
                          __global const float* partials, uint group_count, dt_refine_args args,
                          __global float* correction) {
  __local float sums[DT_REFINE_SUMS];
  if (!s->active) return; /* read by every work-item before the barrier, after which work-item 0 writes it */
  const uint lid = get_local_id(0);
  if (lid < DT_REFINE_SUMS) {
    float sum = 0.0f;
    for (uint g = 0; g < group_count; ++g) sum += partials[DT_CAST(ulong, g) * DT_REFINE_SUMS + lid];
    sums[lid] = sum;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lid != 0) return;
  const dt_vec3 centre = dt_vec3_make(args.centre_x, args.centre_y, args.centre_z);
  float lambda = s->lambda;
  if (s->evaluation == 0 || dt_refine_keeps(sums[DT_REFINE_OBJECTIVE], s->best_sums[DT_REFINE_OBJECTIVE])) {
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
  s->active = 0;
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  const dt_pose start = dt_load_pose(states + DT_CAST(ulong, heaviest) * DT_STATE_STRIDE);
  dt_refine_finish(estimate, start, best, best_sums, s->tried, centre, correction);
}
