/* The pose refinement's pieces shared by its two layouts on the device: cl/refine.cl (the whole fit in one
 * work-group) and cl/refine_spread.cl (each step's rendering and sums over many work-groups, a one-group
 * kernel solving and deciding). The same model, stopping rule and damping as reference::PoseRefiner:
 * IRLS Gauss-Newton steps (each pixel weighted by the responsibility of its visible gaussian over
 * sigma^2) as camera-frame twists about the mesh's centre, each kept unless it lowers the
 * log-likelihood by more than float rounding could, a rejected one damped to lambda >= 1, no step
 * tried that would move no mesh point farther than converged_motion. With args.stages 2 a second stage
 * (Refinement::fine_noise_scale) starts again from the best pose at its own sigma(y) (dt_refine_stage_model)
 * and takes as many steps at most. Needs DT_GROUP_SIZE and DT_OCCLUSION (as weigh.cl). */
#ifndef DT_REFINE_H
#define DT_REFINE_H
#include "dt_group.h"
#include "dt_model.h"
#include "dt_params.h" /* the DT_OCCLUSION codes, dt_refine_args */
#include "dt_pose_twist.h"
#include "dt_refine_state.h"
#include "dt_time_index.h"
#include "dt_window.h"
#include "rasterize.cl"

/* One item of a fit's drawing of pose: items are the triangles times draw_slices, item i draws triangle
 * i mod triangle_count's rows i / triangle_count, then every draw_slices-th (tile, ids and nearest as
 * for dt_raster_triangle_rows). A work-item per whole triangle left a coarse mesh's few large triangles
 * looping over their pixels while the rest of the device waited (H100: the fit's
 * drawing of the gelatin box's 234 triangles took 12 us, of the mug's 3,196 5 us). The depths kept are
 * the same whatever the split: the atomic minimum does not depend on the order. */
DT_DEVICE_FN void dt_refine_draw_item(dt_rigid pose, __global const float* vertices, __global const uint* triangles,
                                      __global const float* planes, uint triangle_count, uint draw_slices, uint item,
                                      dt_camera cam, __global uint* tile, __global uint* ids,
                                      __global dt_u64* nearest) {
  /* Uniform: a mesh drawn whole (most meshes) spends no division per triangle. */
  const uint triangle = draw_slices == 1 ? item : item % triangle_count,
             slice = draw_slices == 1 ? 0u : item / triangle_count;
  dt_draw_triangle_rows(pose, vertices, triangles, planes, triangle, cam, tile, ids, nearest, 0, dt_no_band(),
                        DT_CAST(int, slice), DT_CAST(int, draw_slices));
}

/* Stage `stage`'s observation model and arguments (0: the first, as given; 1: the second, with its own
 * sigma(y) and confidence band, which keeps its width in metres): PoseRefiner's stages (model::fit_stages). */
DT_DEVICE_FN dt_model dt_refine_stage_model(dt_model m, dt_refine_args args, uint stage) {
  if (stage > 0) {
    m.sigma_constant = args.fine_sigma_constant;
    m.sigma_quadratic = args.fine_sigma_quadratic;
  }
  return m;
}
DT_DEVICE_FN dt_refine_args dt_refine_stage_args(dt_refine_args args, uint stage) {
  if (stage > 0) {
    args.pixel_sigmas = args.fine_pixel_sigmas;
    args.step_tolerance = args.fine_step_tolerance;
  }
  return args;
}

/* Solves A x = b for the symmetric 6x6 A given by its lower triangle (row by row), its diagonal times
 * diagonal_factor (1 + lambda for a damped step), scaling it to a
 * unit diagonal first so that float keeps the weakly observed directions; 0 when A is not positive
 * definite. */
DT_DEVICE_FN int dt_solve6(const float* lower, float diagonal_factor, const float* b, float* x) {
  float a[6][6], s[6];
  int k = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j <= i; ++j) {
      a[i][j] = lower[k++];
      a[j][i] = a[i][j];
    }
  for (int i = 0; i < 6; ++i) {
    a[i][i] *= diagonal_factor;
    if (!(a[i][i] > 0.0f)) return 0;
    s[i] = 1.0f / sqrt(a[i][i]);
  }
  float l[6][6], y[6];
  for (int j = 0; j < 6; ++j) {
    float d = a[j][j] * s[j] * s[j];
    for (int m = 0; m < j; ++m) d -= l[j][m] * l[j][m];
    if (!(d > 0.0f)) return 0;
    l[j][j] = sqrt(d);
    for (int i = j + 1; i < 6; ++i) {
      float e = a[i][j] * s[i] * s[j];
      for (int m = 0; m < j; ++m) e -= l[i][m] * l[j][m];
      l[i][j] = e / l[j][j];
    }
  }
  for (int i = 0; i < 6; ++i) {
    float e = b[i] * s[i];
    for (int m = 0; m < i; ++m) e -= l[i][m] * y[m];
    y[i] = e / l[i][i];
  }
  for (int i = 5; i >= 0; --i) {
    float e = y[i];
    for (int m = i + 1; m < 6; ++m) e -= l[m][i] * x[m];
    x[i] = e / l[i][i];
  }
  for (int i = 0; i < 6; ++i) {
    x[i] *= s[i];
    if (!isfinite(x[i])) return 0;
  }
  return 1;
}

/* Object-frame point (x, y, z) in the camera frame. */
DT_DEVICE_FN dt_vec3 dt_vertex_at(dt_rigid m, float x, float y, float z) {
  return dt_vec3_make(dt_dot(m.r0, x, y, z) + m.t.x, dt_dot(m.r1, x, y, z) + m.t.y, dt_dot(m.r2, x, y, z) + m.t.z);
}

/* Where the heaviest particle's occlusion state from before this frame's weigh starts in each map
 * (its row: weigh's parents[heaviest], weigh.cl; rows of the state window's pixels, dt_window.h), and
 * the window, which places pixel k in the row or makes it fresh (the modes without per-particle maps
 * pass one element, read at 0 or not at all). */
typedef struct {
  ulong occlusion, time;
  dt_window win;
} dt_refine_offsets;

DT_DEVICE_FN dt_refine_offsets dt_refine_map_offsets(uint row, dt_window win) {
  const ulong base = DT_CAST(ulong, row) * dt_window_last_row(win); /* the rows before this frame's weigh */
  dt_refine_offsets o;
  o.win = win;
#if DT_OCCLUSION == DT_OCCLUSION_OFF
  o.occlusion = 0;
  o.time = 0;
#elif DT_OCCLUSION == DT_GLOBAL_TIME
  o.occlusion = base;
  o.time = 0;
#else
  o.occlusion = base;
  o.time = base;
#endif
  return o;
}

/* Pixel k's share of the normal equations, added to acc (DT_REFINE_SUMS), for the pose drawn with
 * depth bits and triangle id there (pose, and its centre in the camera frame); the occlusion prior is
 * the heaviest particle's: its state from before this frame's weigh aged to now, which is weigh's
 * prior where the particle's update changed the pixel and its state elsewhere. */
DT_DEVICE_FN void dt_refine_pixel(float* acc, uint k, uint bits, uint id, dt_rigid pose, dt_vec3 centre,
                                  __global const float* observed, __global const float* occlusion,
                                  __global const dt_u16* occlusion_time, __global const float* frame_times,
                                  dt_refine_offsets at, __global const float* planes, uint triangle_count,
                                  dt_camera cam, dt_model m, dt_refine_args args) {
  const float y = observed[k];
  if (bits == DT_NO_SURFACE || !(y > 0.0f) || !isfinite(y)) return;
  const float y_hat = dt_as_float(bits);
  /* The confidence's counts, with y_hat's own depth band (silhouette_shares). */
  const float sigma = dt_depth_sigma(m, y);
  acc[DT_REFINE_MEASURED] += 1.0f;
  if (fabs(y - y_hat) <= args.pixel_sigmas * sigma) acc[DT_REFINE_VISIBLE] += 1.0f;
  float p = 0.0f;
#if DT_OCCLUSION != DT_OCCLUSION_OFF
  const dt_u32 u = k % cam.width, v = k / cam.width;
  const int from = dt_window_from(at.win, dt_window_to(at.win, u, v), u, v);
#endif
#if DT_OCCLUSION == DT_PER_PIXEL_TIME
  p = from >= 0 ? dt_propagate_occlusion(m, occlusion[at.occlusion + from],
                                         args.now - frame_times[occlusion_time[at.time + from]])
                : dt_propagate_occlusion(m, at.win.initial, args.now - frame_times[DT_TIME_NEVER]);
#elif DT_OCCLUSION == DT_GLOBAL_TIME
  p = from >= 0 ? dt_propagate_occlusion(m, occlusion[at.occlusion + from], args.dt)
                : dt_propagate_occlusion(m, at.win.initial, args.now);
#endif
  float posterior;
  acc[DT_REFINE_OBJECTIVE] += dt_pixel_log_ratio(m, y, y_hat, p, &posterior);
  /* E-step: (1 - p) (1 - w) N / mixture = (1 - posterior) (1 - w) N / p_vis. */
  const float z = (y - y_hat) / sigma;
  const float gaussian = m.keep * exp(-0.5f * z * z) / (2.5066282746f * sigma);
  const float responsibility = (1.0f - posterior) * gaussian / (m.tail_density + gaussian);
  if (id >= triangle_count) return; /* no triangle claimed the pixel: no normal to fit with */
  const dt_plane n = dt_triangle_plane(pose, planes, id);
  const float rx = (DT_CAST(float, k % cam.width) - cam.cx) / cam.fx;
  const float ry = (DT_CAST(float, k / cam.width) - cam.cy) / cam.fy;
  const float incidence = n.nx * rx + n.ny * ry + n.nz;
  if (fabs(incidence) < args.min_incidence * sqrt(rx * rx + ry * ry + 1.0f)) return;
  const float lx = y_hat * rx - centre.x, ly = y_hat * ry - centre.y, lz = y_hat - centre.z;
  const float j[6] = {n.nx / incidence,
                      n.ny / incidence,
                      n.nz / incidence,
                      (ly * n.nz - lz * n.ny) / incidence,
                      (lz * n.nx - lx * n.nz) / incidence,
                      (lx * n.ny - ly * n.nx) / incidence};
  const float w = responsibility / (sigma * sigma), r = y - y_hat;
  int h = 0;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b <= a; ++b) acc[h++] += w * j[a] * j[b];
  for (int a = 0; a < 6; ++a) acc[21 + a] += w * j[a] * r;
  acc[DT_REFINE_PIXELS] += 1.0f;
}

/* The refinement's group sums (dt_group_sums of DT_REFINE_SUMS a work-item; a tree of 31 sums a level
 * was a third of refine_sums' time on the H200) need this many floats of work-group memory. */
#define DT_REFINE_SCRATCH DT_GROUP_SUMS_SCRATCH(DT_REFINE_SUMS)

/* The damped step from the best pose's sums into step; 0 when there is none to try (too few pixels, a
 * singular system, or converged: PoseRefiner's step_motion |dt| + radius |dw| below converged_motion). */
DT_DEVICE_FN int dt_refine_step(const float* best_sums, float lambda, dt_refine_args args, float* step) {
  if (!(best_sums[DT_REFINE_PIXELS] >= 6.0f && dt_solve6(best_sums, 1.0f + lambda, best_sums + 21, step))) return 0;
  return sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]) +
             args.radius * sqrt(step[3] * step[3] + step[4] * step[4] + step[5] * step[5]) >=
         args.converged_motion;
}

/* A candidate is kept unless it lowers the objective by more than float rounding could (the stage's
 * tolerance, model::step_tolerance, as PoseRefiner's); otherwise lambda becomes PoseRefiner's
 * damping_after_rejection. */
DT_DEVICE_FN int dt_refine_keeps(float candidate_objective, float best_objective, float tolerance) {
  return candidate_objective >= best_objective - tolerance;
}
DT_DEVICE_FN float dt_refine_damping_after_rejection(float lambda) {
  return fmax(10.0f * lambda, 1.0f);
}

/* The fit's results: the refined pose, the steps tried and its H and pixels (the host makes the covariance) into
 * estimate, and into correction the twist that puts the heaviest particle (start) on the refined pose (see
 * ReferenceFilter::refine). */
DT_DEVICE_FN void dt_refine_finish(__global float* estimate, dt_pose start, dt_pose best, const float* best_sums,
                                   int tried, dt_vec3 centre, __global float* correction) {
  dt_store_pose(estimate, best);
  estimate[DT_EST_REFINE_ITERATIONS] = DT_CAST(float, tried);
  estimate[DT_EST_VISIBLE] = best_sums[DT_REFINE_VISIBLE];
  estimate[DT_EST_MEASURED] = best_sums[DT_REFINE_MEASURED];
  for (int k = 0; k < 21; ++k) estimate[DT_EST_NORMAL + k] = best_sums[k];
  estimate[DT_EST_FIT_PIXELS] = best_sums[DT_REFINE_PIXELS];
  const dt_vec3 from = dt_pose_centre(start, centre), to = dt_pose_centre(best, centre);
  const dt_vec3 rotation = dt_quat_log(dt_quat_mul(best.q, dt_quat_conj(start.q)));
  correction[0] = to.x - from.x;
  correction[1] = to.y - from.y;
  correction[2] = to.z - from.z;
  correction[3] = rotation.x;
  correction[4] = rotation.y;
  correction[5] = rotation.z;
}
#endif
