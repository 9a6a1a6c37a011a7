/* Pose refinement on the device, in one work-group of DT_GROUP_SIZE: from the heaviest particle, damped
 * Gauss-Newton steps on the per-pixel likelihood with the heaviest particle's occlusion prior (IRLS:
 * each pixel weighted by the responsibility of its visible gaussian over sigma^2), each step a
 * camera-frame twist about the mesh's centre. Every candidate pose is drawn into one tile with the
 * atlas rasterizer, then drawn again to learn each pixel's triangle (for its normal); the normal
 * equations are a group sum and work-item 0 solves them (Cholesky of the diagonally scaled system)
 * and keeps each step unless it lowers the log-likelihood; it stops when the next step would move no
 * mesh point farther than converged_motion. No host round trip: the estimate
 * buffer receives the refined pose and its covariance, `correction` the twist that resample_particles applies to every
 * particle (the one that moves the heaviest particle onto the refined pose). Compile-time choices as for weigh.cl
 * (DT_GROUP_SIZE, DT_OCCLUSION); the pieces shared with cl/refine_spread.cl are in dt_refine.h.
 * With args.stages 2 the steps run again from the best pose at the second stage's noise (dt_refine.h).
 * Reference: PoseRefiner::refine and ReferenceFilter::refine. */
#include "dt_refine.h"

/* Draws the pose in pose_state into tile (depth bits, DT_NO_SURFACE where empty) and each covered
 * pixel's triangle into ids, then sums the normal equations over the group into sums[k]. */
DT_DEVICE_FN void dt_refine_evaluate(__global const float* pose_state, __global const float* observed,
                                     __global const float* occlusion, __global const dt_u16* occlusion_time,
                                     __global const float* frame_times, dt_refine_offsets at,
                                     __global const float* vertices, __global const uint* triangles,
                                     __global const float* planes, uint triangle_count, dt_camera cam, dt_model m,
                                     dt_refine_args args, __global uint* tile, __global uint* ids,
                                     DT_LOCAL_PTR float* sums) {
  const uint lid = get_local_id(0);
  const dt_rigid pose = dt_particle_pose(pose_state);
  /* Only the pose's box is cleared and summed: the silhouette is a small part of the image, and no
   * triangle draws outside the box. */
  int in_front;
  const dt_pixel_box box = dt_pose_box(pose, vertices, args.vertex_count, cam, sums, 0, &in_front);
  const uint pixels = box.width * box.height;
  for (uint b = lid; b < pixels; b += DT_GROUP_SIZE) {
    const uint k = dt_box_pixel(box, b, cam);
    tile[k] = DT_NO_SURFACE;
    ids[k] = 0xffffffffu;
  }
  barrier(CLK_GLOBAL_MEM_FENCE);
  const uint items = triangle_count * args.draw_slices;
  for (uint item = lid; item < items; item += DT_GROUP_SIZE)
    dt_refine_draw_item(pose, vertices, triangles, planes, triangle_count, args.draw_slices, item, cam, tile, 0, 0);
  barrier(CLK_GLOBAL_MEM_FENCE);
  for (uint item = lid; item < items; item += DT_GROUP_SIZE)
    dt_refine_draw_item(pose, vertices, triangles, planes, triangle_count, args.draw_slices, item, cam, tile, ids, 0);
  barrier(CLK_GLOBAL_MEM_FENCE);

  const dt_vec3 centre = dt_vertex_at(pose, args.centre_x, args.centre_y, args.centre_z);
  float acc[DT_REFINE_SUMS];
  for (int k = 0; k < DT_REFINE_SUMS; ++k) acc[k] = 0.0f;
  for (uint b = lid; b < pixels; b += DT_GROUP_SIZE) {
    const uint k = dt_box_pixel(box, b, cam);
    dt_refine_pixel(acc, k, tile[k], ids[k], pose, centre, observed, occlusion, occlusion_time, frame_times, at, planes,
                    triangle_count, cam, m, args);
  }
  dt_group_sums(acc, DT_REFINE_SUMS, sums);
}

/* estimate: holds summarize's heaviest particle and receives the refined pose and its covariance
 * (dt_state.h); states: the particles; occlusion, occlusion_time: the per-pixel state from before this
 * frame's weigh, particle i's in row parents[i] (the heaviest particle's prior is its row aged to now);
 * pose_state, tile and ids: scratch for one pose; correction: the twist from the heaviest particle to
 * the refined pose; win: the state window, which places each pixel's state in those rows. */
__kernel void refine(__global float* estimate, __global const float* states, __global const float* observed,
                     __global const float* occlusion, __global const dt_u16* occlusion_time,
                     __global const float* frame_times, __global const uint* parents, __global const float* vertices,
                     __global const uint* triangles, __global const float* planes, uint triangle_count, dt_camera cam,
                     dt_model m, dt_refine_args args, __global float* pose_state, __global uint* tile,
                     __global uint* ids, __global float* correction, dt_window win) {
  __local float sums[DT_REFINE_SCRATCH];
  __local int proceed;
  int tried = 0; /* work-item 0's count of steps evaluated */
  const uint lid = get_local_id(0);
  const dt_vec3 centre = dt_vec3_make(args.centre_x, args.centre_y, args.centre_z);

  /* summarize found it (the first of equal maximal log weights, as the reference): not searched again. */
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  const dt_refine_offsets at = dt_refine_map_offsets(parents[heaviest], win);

  const dt_pose start = dt_load_pose(states + DT_CAST(ulong, heaviest) * DT_STATE_STRIDE);
  /* Work-item 0's: the best pose evaluated, its sums, the damping. */
  dt_pose best = start;
  float best_sums[DT_REFINE_SUMS];
  for (uint stage = 0; stage < args.stages; ++stage) {
    const dt_model sm = dt_refine_stage_model(m, args, stage);
    const dt_refine_args sa = dt_refine_stage_args(args, stage);
    /* Each stage starts from the best pose so far, its sums at the stage's noise (work-item 0 has read
     * the last stage's sums before the barrier). */
    if (lid == 0) dt_store_pose(pose_state, best);
    barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
    dt_refine_evaluate(pose_state, observed, occlusion, occlusion_time, frame_times, at, vertices, triangles, planes,
                       triangle_count, cam, sm, sa, tile, ids, sums);
    float lambda = args.damping;
    if (lid == 0)
      for (int k = 0; k < DT_REFINE_SUMS; ++k) best_sums[k] = sums[k];
    for (int iteration = 0; iteration < args.iterations; ++iteration) {
      if (lid == 0) {
        float step[6];
        proceed = dt_refine_step(best_sums, lambda, args, step);
        if (proceed) {
          dt_store_pose(pose_state, dt_apply_twist(best, centre, step));
          ++tried;
        }
      }
      barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
      if (!proceed) break;
      dt_refine_evaluate(pose_state, observed, occlusion, occlusion_time, frame_times, at, vertices, triangles, planes,
                         triangle_count, cam, sm, sa, tile, ids, sums);
      if (lid == 0) {
        if (dt_refine_keeps(sums[DT_REFINE_OBJECTIVE], best_sums[DT_REFINE_OBJECTIVE], sa.step_tolerance)) {
          best = dt_load_pose(pose_state);
          for (int k = 0; k < DT_REFINE_SUMS; ++k) best_sums[k] = sums[k];
          lambda = args.damping;
        } else {
          lambda = dt_refine_damping_after_rejection(lambda);
        }
      }
    }
  }
  if (lid == 0) dt_refine_finish(estimate, start, best, best_sums, tried, centre, correction);
}
