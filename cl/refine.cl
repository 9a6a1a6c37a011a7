/* Pose refinement on the device, in one work-group of DT_GROUP_SIZE: from the heaviest particle, damped
 * Gauss-Newton steps on the per-pixel likelihood with the heaviest particle's occlusion prior (IRLS:
 * each pixel weighted by the responsibility of its visible gaussian over sigma^2), each step a
 * camera-frame twist about the mesh's centre. Every candidate pose is drawn into one tile with the
 * atlas rasterizer, then drawn again to learn each pixel's triangle (for its normal); the normal
 * equations are a group sum and work-item 0 solves them (Cholesky of the diagonally scaled system)
 * and keeps each step unless it lowers the log-likelihood; it stops when the next step would move no
 * mesh point farther than converged_motion. No host round trip: the estimate
 * buffer receives the refined pose and its covariance, `correction` the twist that shift_particles applies to every
 * particle (the one that moves the heaviest particle onto the refined pose). Compile-time choices as for weigh.cl
 * (DT_GROUP_SIZE, DT_OCCLUSION). Reference: PoseRefiner::refine and ReferenceFilter::refine. */
#include "dt_group.h"
#include "dt_model.h"
#include "dt_params.h" /* the DT_OCCLUSION codes */
#include "rasterize.cl"

#define DT_REFINE_SUMS 29 /* H's lower triangle (21), g (6), objective, pixels */
#define DT_REFINE_OBJECTIVE 27
#define DT_REFINE_PIXELS 28

typedef struct {
  float damping;       /* Levenberg-Marquardt lambda on diag(H) */
  float min_incidence; /* pixels with |cos(normal, ray)| below it are left out of H */
  float centre_x, centre_y, centre_z;
  float now;              /* seconds since the first frame: the per-pixel-time occlusion mode ages p to it */
  int iterations;         /* damped steps at most */
  float radius;           /* largest vertex distance from the centre */
  float converged_motion; /* a step moving no mesh point farther than this (metres) is not tried */
  uint vertex_count;
} dt_refine_args;

/* The pixels a pose can cover: its projected vertices' bounding box, a pixel wider on each side (the
 * triangle passes project the same vertices, maybe contracted into FMAs differently), clamped to
 * the image; the whole image when a vertex lies before the near plane (cut triangles). */
typedef struct {
  uint u0, v0, width, height; /* empty: width or height 0 */
} dt_pixel_box;

DT_DEVICE_FN dt_pixel_box dt_pose_box(dt_rigid pose, __global const float* vertices, uint vertex_count, dt_camera cam,
                                      DT_LOCAL_PTR float* scratch) {
  const uint lid = get_local_id(0);
  /* minima of u, v, -u, -v and of "every vertex in front" as 0/-1 */
  float low[5] = {-DT_LOWEST, -DT_LOWEST, -DT_LOWEST, -DT_LOWEST, 0.0f};
  for (uint i = lid; i < vertex_count; i += DT_GROUP_SIZE) {
    const dt_vec3 p = dt_vertex(pose, vertices, i);
    if (!(p.z >= cam.near)) {
      low[4] = -1.0f;
      continue;
    }
    const dt_point s = dt_project(p, cam);
    low[0] = fmin(low[0], s.u);
    low[1] = fmin(low[1], s.v);
    low[2] = fmin(low[2], -s.u);
    low[3] = fmin(low[3], -s.v);
  }
  barrier(CLK_LOCAL_MEM_FENCE); /* the previous use of scratch is over */
  for (int k = 0; k < 5; ++k) scratch[k * DT_GROUP_SIZE + lid] = low[k];
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint stride = DT_GROUP_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride)
      for (int k = 0; k < 5; ++k)
        scratch[k * DT_GROUP_SIZE + lid] =
            fmin(scratch[k * DT_GROUP_SIZE + lid], scratch[k * DT_GROUP_SIZE + lid + stride]);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  dt_pixel_box box;
  box.u0 = 0;
  box.v0 = 0;
  box.width = cam.width;
  box.height = cam.height;
  if (scratch[4 * DT_GROUP_SIZE] == 0.0f) {
    /* clamped in float before the conversion to int, as dt_raster_triangle does */
    const float last_u = DT_CAST(float, cam.width - 1), last_v = DT_CAST(float, cam.height - 1);
    const float u0 = fmin(fmax(0.0f, floor(scratch[0]) - 1.0f), last_u + 1.0f);
    const float v0 = fmin(fmax(0.0f, floor(scratch[DT_GROUP_SIZE]) - 1.0f), last_v + 1.0f);
    const float u1 = fmax(fmin(last_u, ceil(-scratch[2 * DT_GROUP_SIZE]) + 1.0f), -1.0f);
    const float v1 = fmax(fmin(last_v, ceil(-scratch[3 * DT_GROUP_SIZE]) + 1.0f), -1.0f);
    box.u0 = DT_CAST(uint, u0);
    box.v0 = DT_CAST(uint, v0);
    box.width = u1 >= u0 ? DT_CAST(uint, u1 - u0) + 1 : 0;
    box.height = v1 >= v0 ? DT_CAST(uint, v1 - v0) + 1 : 0;
  }
  return box;
}

/* The image index of the box's k-th pixel (row by row). */
DT_DEVICE_FN uint dt_box_pixel(dt_pixel_box box, uint k, dt_camera cam) {
  return (box.v0 + k / box.width) * cam.width + box.u0 + k % box.width;
}

/* Pose as translation and unit quaternion, in a work-item's registers. */
typedef struct {
  dt_vec3 t;
  dt_quat q;
} dt_pose;

DT_DEVICE_FN dt_vec3 dt_pose_centre(dt_pose p, dt_vec3 centre) {
  const dt_vec3 c = dt_quat_rotate(p.q, centre);
  return dt_vec3_make(c.x + p.t.x, c.y + p.t.y, c.z + p.t.z);
}

/* The pose moved by the camera-frame twist (dt, dw) about centre (object frame). */
DT_DEVICE_FN dt_pose dt_apply_twist(dt_pose p, dt_vec3 centre, const float* twist) {
  const dt_vec3 c = dt_pose_centre(p, centre);
  dt_pose r;
  r.q = dt_quat_normalize(dt_quat_mul(dt_quat_exp(dt_vec3_make(twist[3], twist[4], twist[5])), p.q));
  const dt_vec3 rc = dt_quat_rotate(r.q, centre);
  r.t = dt_vec3_make(c.x + twist[0] - rc.x, c.y + twist[1] - rc.y, c.z + twist[2] - rc.z);
  return r;
}

DT_DEVICE_FN void dt_store_pose(__global float* s, dt_pose p) {
  s[DT_TX] = p.t.x;
  s[DT_TX + 1] = p.t.y;
  s[DT_TX + 2] = p.t.z;
  s[DT_QW] = p.q.w;
  s[DT_QW + 1] = p.q.x;
  s[DT_QW + 2] = p.q.y;
  s[DT_QW + 3] = p.q.z;
}

DT_DEVICE_FN dt_pose dt_load_pose(__global const float* s) {
  dt_pose p;
  p.t = dt_vec3_make(s[DT_TX], s[DT_TX + 1], s[DT_TX + 2]);
  p.q.w = s[DT_QW];
  p.q.x = s[DT_QW + 1];
  p.q.y = s[DT_QW + 2];
  p.q.z = s[DT_QW + 3];
  return p;
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

/* Draws the pose in pose_state into tile (depth bits, DT_NO_SURFACE where empty) and each covered
 * pixel's triangle into ids, then sums the normal equations over the group into sums[k * G]. */
DT_DEVICE_FN void dt_refine_evaluate(__global const float* pose_state, __global const float* observed,
                                     __global const float* occlusion, __global const float* occlusion_time,
                                     __global const float* prior, __global const float* atlas, dt_atlas_layout layout,
                                     ulong heaviest_tile, __global const float* vertices,
                                     __global const uint* triangles, __global const float* planes, uint triangle_count,
                                     dt_camera cam, dt_model m, dt_refine_args args, __global uint* tile,
                                     __global uint* ids, DT_LOCAL_PTR float* sums) {
  const uint lid = get_local_id(0);
  const dt_rigid pose = dt_particle_pose(pose_state);
  /* Only the pose's box is cleared and summed: the silhouette is a small part of the image, and no
   * triangle draws outside the box. */
  const dt_pixel_box box = dt_pose_box(pose, vertices, args.vertex_count, cam, sums);
  const uint pixels = box.width * box.height;
  for (uint b = lid; b < pixels; b += DT_GROUP_SIZE) {
    const uint k = dt_box_pixel(box, b, cam);
    tile[k] = DT_NO_SURFACE;
    ids[k] = 0xffffffffu;
  }
  barrier(CLK_GLOBAL_MEM_FENCE);
  for (uint t = lid; t < triangle_count; t += DT_GROUP_SIZE)
    dt_draw_triangle(pose, vertices, triangles, planes, t, cam, tile, 0);
  barrier(CLK_GLOBAL_MEM_FENCE);
  for (uint t = lid; t < triangle_count; t += DT_GROUP_SIZE)
    dt_draw_triangle(pose, vertices, triangles, planes, t, cam, tile, ids);
  barrier(CLK_GLOBAL_MEM_FENCE);

  const dt_vec3 centre = dt_vertex_at(pose, args.centre_x, args.centre_y, args.centre_z);
  float acc[DT_REFINE_SUMS];
  for (int k = 0; k < DT_REFINE_SUMS; ++k) acc[k] = 0.0f;
  for (uint b = lid; b < pixels; b += DT_GROUP_SIZE) {
    const uint k = dt_box_pixel(box, b, cam);
    const uint bits = tile[k];
    const float y = observed[k];
    if (bits == DT_NO_SURFACE || !(y > 0.0f) || !isfinite(y)) continue;
    const float y_hat = dt_as_float(bits);
    /* The heaviest particle's occlusion prior: kept by weigh where its update changed the pixel. */
    float p = 0.0f;
#if DT_OCCLUSION != DT_OCCLUSION_OFF
    if (atlas[dt_atlas_pixel(layout, heaviest_tile, k)] > 0.0f)
      p = prior[k];
    else
#if DT_OCCLUSION == DT_PER_PIXEL_TIME
      p = dt_propagate_occlusion(m, occlusion[k], args.now - occlusion_time[k]);
#else
      p = occlusion[k];
#endif
#endif
    float posterior;
    acc[DT_REFINE_OBJECTIVE] += dt_pixel_log_ratio(m, y, y_hat, p, &posterior);
    /* E-step: (1 - p) (1 - w) N / mixture = (1 - posterior) (1 - w) N / p_vis. */
    const float sigma = m.sigma_constant + m.sigma_quadratic * y * y;
    const float z = (y - y_hat) / sigma;
    const float gaussian = m.keep * exp(-0.5f * z * z) / (2.5066282746f * sigma);
    const float responsibility = (1.0f - posterior) * gaussian / (m.tail_density + gaussian);
    if (ids[k] >= triangle_count) continue; /* no triangle claimed the pixel: no normal to fit with */
    const dt_plane n = dt_triangle_plane(pose, planes, ids[k]);
    const float rx = (DT_CAST(float, k % cam.width) - cam.cx) / cam.fx;
    const float ry = (DT_CAST(float, k / cam.width) - cam.cy) / cam.fy;
    const float incidence = n.nx * rx + n.ny * ry + n.nz;
    if (fabs(incidence) < args.min_incidence * sqrt(rx * rx + ry * ry + 1.0f)) continue;
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
  barrier(CLK_LOCAL_MEM_FENCE); /* the previous sums have been read */
  for (int k = 0; k < DT_REFINE_SUMS; ++k) sums[k * DT_GROUP_SIZE + lid] = acc[k];
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint stride = DT_GROUP_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride)
      for (int k = 0; k < DT_REFINE_SUMS; ++k) sums[k * DT_GROUP_SIZE + lid] += sums[k * DT_GROUP_SIZE + lid + stride];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
}

/* estimate: holds summarize's heaviest particle and receives the refined pose and its covariance
 * (dt_state.h); states: the particles (the heaviest particle's occlusion prior is used: weigh's prior
 * where the particle's tile in atlas covers the pixel, its state elsewhere); pose_state, tile and ids:
 * scratch for one pose; correction: the twist from the heaviest particle to the refined pose. */
__kernel void refine(__global float* estimate, __global const float* states, __global const float* observed,
                     __global const float* occlusion, __global const float* occlusion_time, __global const float* prior,
                     __global const float* atlas, dt_atlas_layout layout, __global const float* vertices,
                     __global const uint* triangles, __global const float* planes, uint triangle_count, dt_camera cam,
                     dt_model m, dt_refine_args args, __global float* pose_state, __global uint* tile,
                     __global uint* ids, __global float* correction) {
  __local float sums[DT_REFINE_SUMS * DT_GROUP_SIZE];
  __local int proceed;
  int tried = 0; /* work-item 0's count of steps evaluated */
  const uint lid = get_local_id(0), pixels = cam.width * cam.height;
  const dt_vec3 centre = dt_vec3_make(args.centre_x, args.centre_y, args.centre_z);

  /* summarize found it (the first of equal maximal log weights, as the reference): not searched again. */
  const uint heaviest = dt_as_uint(estimate[DT_EST_HEAVIEST]);
  const ulong base = DT_CAST(ulong, heaviest) * pixels;
#if DT_OCCLUSION == DT_OCCLUSION_OFF
  __global const float* p_map = occlusion;
  __global const float* t_map = occlusion_time;
  __global const float* prior_map = prior;
#elif DT_OCCLUSION == DT_GLOBAL_TIME
  __global const float* p_map = occlusion + base;
  __global const float* t_map = occlusion_time;
  __global const float* prior_map = prior + base;
#else
  __global const float* p_map = occlusion + base;
  __global const float* t_map = occlusion_time + base;
  __global const float* prior_map = prior + base;
#endif
  const ulong heaviest_tile = dt_atlas_tile_start(layout, heaviest);

  const dt_pose start = dt_load_pose(states + DT_CAST(ulong, heaviest) * DT_STATE_STRIDE);
  if (lid == 0) dt_store_pose(pose_state, start);
  barrier(CLK_GLOBAL_MEM_FENCE);
  dt_refine_evaluate(pose_state, observed, p_map, t_map, prior_map, atlas, layout, heaviest_tile, vertices, triangles,
                     planes, triangle_count, cam, m, args, tile, ids, sums);
  /* Work-item 0's: the best pose evaluated, its sums, the damping. */
  dt_pose best = start;
  float best_sums[DT_REFINE_SUMS];
  float lambda = args.damping;
  if (lid == 0)
    for (int k = 0; k < DT_REFINE_SUMS; ++k) best_sums[k] = sums[k * DT_GROUP_SIZE];
  for (int iteration = 0; iteration < args.iterations; ++iteration) {
    if (lid == 0) {
      float step[6];
      proceed = best_sums[DT_REFINE_PIXELS] >= 6.0f && dt_solve6(best_sums, 1.0f + lambda, best_sums + 21, step);
      /* PoseRefiner's step_motion: |dt| + radius |dw| */
      if (proceed)
        proceed = sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]) +
                      args.radius * sqrt(step[3] * step[3] + step[4] * step[4] + step[5] * step[5]) >=
                  args.converged_motion;
      if (proceed) {
        dt_store_pose(pose_state, dt_apply_twist(best, centre, step));
        ++tried;
      }
    }
    barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
    if (!proceed) break;
    dt_refine_evaluate(pose_state, observed, p_map, t_map, prior_map, atlas, layout, heaviest_tile, vertices, triangles,
                       planes, triangle_count, cam, m, args, tile, ids, sums);
    if (lid == 0) {
      /* Kept unless it lowers the objective by more than float rounding could (PoseRefiner's tolerance). */
      if (sums[DT_REFINE_OBJECTIVE * DT_GROUP_SIZE] >= best_sums[DT_REFINE_OBJECTIVE] - 0.01f) {
        best = dt_load_pose(pose_state);
        for (int k = 0; k < DT_REFINE_SUMS; ++k) best_sums[k] = sums[k * DT_GROUP_SIZE];
        lambda = args.damping;
      } else {
        lambda = fmax(10.0f * lambda, 1.0f); /* a rejected step: PoseRefiner's damping_after_rejection */
      }
    }
  }

  if (lid == 0) {
    dt_store_pose(estimate, best);
    estimate[DT_EST_REFINE_ITERATIONS] = DT_CAST(float, tried);
    const float nan = dt_as_float(0x7fc00000u);
    for (int c = 0; c < 6; ++c) {
      float unit[6] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f}, column[6];
      unit[c] = 1.0f;
      const int ok = best_sums[DT_REFINE_PIXELS] >= 6.0f && dt_solve6(best_sums, 1.0f, unit, column);
      for (int r = 0; r < 6; ++r) estimate[DT_EST_COV + 6 * r + c] = ok ? column[r] : nan;
    }
    /* The twist that puts the heaviest particle on the refined pose (see ReferenceFilter::refine). */
    const dt_pose heaviest_pose = dt_load_pose(states + DT_CAST(ulong, heaviest) * DT_STATE_STRIDE);
    const dt_vec3 from = dt_pose_centre(heaviest_pose, centre), to = dt_pose_centre(best, centre);
    const dt_vec3 rotation = dt_quat_log(dt_quat_mul(best.q, dt_quat_conj(heaviest_pose.q)));
    correction[0] = to.x - from.x;
    correction[1] = to.y - from.y;
    correction[2] = to.z - from.z;
    correction[3] = rotation.x;
    correction[4] = rotation.y;
    correction[5] = rotation.z;
  }
}

/* Every particle moved by the same twist about its own centre: the cloud follows the refinement.
 * from and to may be the same buffer; velocities are copied unchanged. */
__kernel void shift_particles(__global const float* from, __global float* to, uint count,
                              __global const float* correction, float centre_x, float centre_y, float centre_z) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  __global const float* s = from + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  __global float* d = to + DT_CAST(ulong, i) * DT_STATE_STRIDE;
  const float twist[6] = {correction[0], correction[1], correction[2], correction[3], correction[4], correction[5]};
  const dt_pose moved = dt_apply_twist(dt_load_pose(s), dt_vec3_make(centre_x, centre_y, centre_z), twist);
  for (int k = DT_VX; k < DT_STATE_STRIDE; ++k) d[k] = s[k];
  dt_store_pose(d, moved);
}
