/* The pose atlas rasterized on the compute device: a work-group per particle, its work-items striding
 * over the mesh's triangles. Each rasterizes its triangle's pixel box and keeps the nearest depth
 * with an atomic minimum on the float's bits (positive floats order like their bit patterns).
 * Conventions of reference::Rasterizer, in float: a pixel is covered when its centre lies inside the
 * projected triangle (top-left rule on ties), its depth is that of the triangle's plane along the
 * ray through the centre, triangles are cut at z = near, depths beyond far discarded, back faces
 * culled where the mesh bounds a solid (dt_camera.cull_back_faces).
 * The depths are kept in the atlas itself: a tile in local memory measured no faster (PoCL: equal;
 * H100: 5 % faster for the handset, 7-16 % slower for the 69k-triangle bunny, as it lowers occupancy)
 * and fits only up to about 100x100 pixels. DT_GROUP_SIZE: work-items per group.
 * Reference: Rasterizer::render. */
#include "dt_prelude.h"
#include "dt_launch.h"
#ifndef DT_GROUP_SIZE
#define DT_GROUP_SIZE DT_FILTER_GROUP
#endif
#include "dt_atlas.h"
#include "dt_quaternion.h"
#include "dt_state.h"
#include "dt_params.h" /* dt_camera */
#include "dt_pixel_box.h"

#define DT_NO_SURFACE 0x7f800000u /* +inf's bits: above every depth until the end, then 0 */

typedef struct {
  float u, v;
} dt_point;

/* An edge's function w(p) = s ((b - a) x (p - a)), evaluated from the lexicographically smaller end
 * (o, direction d, sign s): the two triangles sharing an edge get exactly opposite values, so float
 * rounding opens no crack between them and covers no pixel twice. */
typedef struct {
  float ou, ov, du, dv, sign;
  int owned; /* top-left rule: a centre exactly on the edge belongs to this triangle */
} dt_edge;

DT_DEVICE_FN dt_edge dt_make_edge(dt_point a, dt_point b) {
  const int forward = a.u < b.u || (a.u == b.u && a.v < b.v);
  const dt_point o = forward ? a : b, e = forward ? b : a;
  dt_edge r;
  r.ou = o.u;
  r.ov = o.v;
  r.du = e.u - o.u;
  r.dv = e.v - o.v;
  r.sign = forward ? 1.0f : -1.0f;
  const float dv = b.v - a.v, du = b.u - a.u;
  r.owned = dv < 0.0f || (dv == 0.0f && du > 0.0f);
  return r;
}

DT_DEVICE_FN float dt_edge_at(dt_edge e, float u, float v) {
  return e.sign * dt_mul_add(e.du, v - e.ov, -(e.dv * (u - e.ou)));
}

DT_DEVICE_FN int dt_edge_admits(dt_edge e, float u, float v) {
  const float w = dt_edge_at(e, u, v);
  return w > 0.0f || (w == 0.0f && e.owned);
}

/* The camera-frame plane n . x = d of the triangle being drawn. */
typedef struct {
  float nx, ny, nz, d;
} dt_plane;

/* camera_from_object as the rows of [R | t]. */
typedef struct {
  dt_vec3 r0, r1, r2, t;
} dt_rigid;

DT_DEVICE_FN float dt_dot(dt_vec3 a, float x, float y, float z) {
  return dt_mul_add(a.z, z, dt_mul_add(a.y, y, a.x * x));
}

/* The particle's pose, R of the normalized quaternion as atlas.vert forms it. */
DT_DEVICE_FN dt_rigid dt_particle_pose(__global const float* s) {
  dt_quat q;
  q.w = s[DT_QW];
  q.x = s[DT_QW + 1];
  q.y = s[DT_QW + 2];
  q.z = s[DT_QW + 3];
  q = dt_quat_normalize(q);
  dt_rigid m;
  m.r0 = dt_vec3_make(1.0f - 2.0f * (q.y * q.y + q.z * q.z), 2.0f * (q.x * q.y - q.w * q.z),
                      2.0f * (q.x * q.z + q.w * q.y));
  m.r1 = dt_vec3_make(2.0f * (q.x * q.y + q.w * q.z), 1.0f - 2.0f * (q.x * q.x + q.z * q.z),
                      2.0f * (q.y * q.z - q.w * q.x));
  m.r2 = dt_vec3_make(2.0f * (q.x * q.z - q.w * q.y), 2.0f * (q.y * q.z + q.w * q.x),
                      1.0f - 2.0f * (q.x * q.x + q.y * q.y));
  m.t = dt_vec3_make(s[DT_TX], s[DT_TX + 1], s[DT_TX + 2]);
  return m;
}

/* Vertex i of the mesh in the camera frame. */
DT_DEVICE_FN dt_vec3 dt_vertex(dt_rigid m, __global const float* vertices, uint i) {
  __global const float* x = vertices + 3 * DT_CAST(ulong, i);
  return dt_vec3_make(dt_dot(m.r0, x[0], x[1], x[2]) + m.t.x, dt_dot(m.r1, x[0], x[1], x[2]) + m.t.y,
                      dt_dot(m.r2, x[0], x[1], x[2]) + m.t.z);
}

/* Triangle i's plane in the camera frame from its object-frame n and d: n' = R n, d' = d + n' . t. */
DT_DEVICE_FN dt_plane dt_triangle_plane(dt_rigid m, __global const float* planes, uint i) {
  __global const float* o = planes + 4 * DT_CAST(ulong, i);
  dt_plane p;
  p.nx = dt_dot(m.r0, o[0], o[1], o[2]);
  p.ny = dt_dot(m.r1, o[0], o[1], o[2]);
  p.nz = dt_dot(m.r2, o[0], o[1], o[2]);
  p.d = dt_mul_add(p.nz, m.t.z, dt_mul_add(p.ny, m.t.y, dt_mul_add(p.nx, m.t.x, o[3])));
  return p;
}

/* The pixel centres in projected triangle abc's bounding box, [u0, u1] x [v0, v1], clamped in float to
 * [-1, size] before the conversion to int, which is undefined beyond int's range (PoCL then looped over
 * 2^31 columns); a box off the image comes out empty. Whether it holds any: most triangles of a fine
 * mesh hold no centre. */
DT_DEVICE_FN int dt_centre_range(dt_point a, dt_point b, dt_point c, dt_camera cam, int* u0, int* u1, int* v0,
                                 int* v1) {
  const float last_u = DT_CAST(float, cam.width - 1), last_v = DT_CAST(float, cam.height - 1);
  *u0 = DT_CAST(int, fmin(fmax(0.0f, ceil(fmin(a.u, fmin(b.u, c.u)))), last_u + 1.0f));
  *u1 = DT_CAST(int, fmax(fmin(last_u, floor(fmax(a.u, fmax(b.u, c.u)))), -1.0f));
  *v0 = DT_CAST(int, fmin(fmax(0.0f, ceil(fmin(a.v, fmin(b.v, c.v)))), last_v + 1.0f));
  *v1 = DT_CAST(int, fmax(fmin(last_v, floor(fmax(a.v, fmax(b.v, c.v)))), -1.0f));
  return *u0 <= *u1 && *v0 <= *v1;
}

/* Whether a triangle of twice this signed area in the image is drawn: not degenerate, and facing the
 * camera where cam culls the back faces (wound outward, a triangle facing the camera runs clockwise in the
 * image, v down: area < 0). */
DT_DEVICE_FN int dt_drawn_facing(float area, dt_camera cam) {
  return area != 0.0f && isfinite(area) && !(cam.cull_back_faces && area > 0.0f);
}

/* Keeps, at every pixel of the tile whose centre lies inside triangle abc, the nearer of its depth
 * and the tile's. With ids (a second pass over a finished tile, for the pose refinement), it instead
 * writes triangle where its depth is the tile's (to 1e-6 relative): the lowest such index wins, as
 * atomic min. With nearest (the refinement's one pass, where 64-bit atomics exist: programs defining
 * DT_NEAREST_PACKED), it keeps depth bits and triangle together, (bits << 32) | triangle, by a 64-bit
 * atomic min: the nearest depth and, on a tie, the lowest index, as the reference's strict `<` in
 * triangle order. With local_tile (render_weigh.cl's tile in work-group memory) it keeps the nearer
 * depth there, as tile does in global memory, for the pixels of band only (a box's rows, stored row by
 * row at the band's own width): the pixels a pose covers may be more than the tile holds. */
/* With skip_rows, row_count and row_step, only those of its rows: row_count rows, every row_step-th, from the
 * (skip_rows + 1)-th it would draw (render_weigh.cl hands a large triangle's rows to different work-items, the
 * fit's drawing every row_step-th row to each of row_step work-items). */
DT_DEVICE_FN void dt_raster_triangle_rows(dt_point a, dt_point b, dt_point c, dt_rigid pose,
                                          __global const float* planes, dt_camera cam, __global uint* tile,
                                          __global uint* ids, __global dt_u64* nearest, DT_LOCAL_PTR uint* local_tile,
                                          dt_pixel_box band, uint triangle, int skip_rows, int row_count,
                                          int row_step) {
  const float area = dt_edge_at(dt_make_edge(a, b), c.u, c.v);
  if (!dt_drawn_facing(area, cam)) return;
  int u0, u1, v0, v1;
  if (!dt_centre_range(a, b, c, cam, &u0, &u1, &v0, &v1)) return;
  if (local_tile) { /* the band's pixels only: a box's rows, as many as the tile holds */
    u0 = max(u0, DT_CAST(int, band.u0));
    u1 = min(u1, DT_CAST(int, band.u0 + band.width) - 1);
    v0 = max(v0, DT_CAST(int, band.v0));
    v1 = min(v1, DT_CAST(int, band.v0 + band.height) - 1);
    if (u0 > u1 || v0 > v1) return;
  }
  v0 += skip_rows;
  if (v0 > v1) return;
  /* (v0 + row_count may pass int's range: only reached when the rows left are fewer) */
  if ((v1 - v0) / row_step >= row_count) v1 = v0 + (row_count - 1) * row_step;
  if (area < 0.0f) { /* give every triangle drawn the same orientation */
    const dt_point t = b;
    b = c;
    c = t;
  }
  const dt_edge bc = dt_make_edge(b, c), ca = dt_make_edge(c, a), ab = dt_make_edge(a, b);
  /* Only now the plane: most triangles of a fine mesh hold no pixel centre and never need it. */
  const dt_plane plane = dt_triangle_plane(pose, planes, triangle);
  const float inverse_fx = 1.0f / cam.fx, inverse_fy = 1.0f / cam.fy;
  for (int v = v0; v <= v1; v += row_step) {
    const float pv = DT_CAST(float, v), ray_y = (pv - cam.cy) * inverse_fy;
    for (int u = u0; u <= u1; ++u) {
      const float pu = DT_CAST(float, u);
      if (!dt_edge_admits(bc, pu, pv) || !dt_edge_admits(ca, pu, pv) || !dt_edge_admits(ab, pu, pv)) continue;
      const float z =
          dt_divide(plane.d, dt_mul_add(plane.ny, ray_y, plane.nx * ((pu - cam.cx) * inverse_fx)) + plane.nz);
      if (!(z >= cam.near && z <= cam.far)) continue;
      const uint k = DT_CAST(uint, v) * cam.width + DT_CAST(uint, u);
      if (local_tile) {
        dt_atomic_min_u32(local_tile + (DT_CAST(uint, v) - band.v0) * band.width + (DT_CAST(uint, u) - band.u0),
                          dt_as_uint(z));
      } else if (nearest) {
#ifdef DT_NEAREST_PACKED
        dt_atomic_min_u64(nearest + k, (DT_CAST(dt_u64, dt_as_uint(z)) << 32) | triangle);
#endif
      } else if (ids) {
        /* Within a few ulps, not bit for bit: NVRTC contracts this pass's arithmetic into FMAs
         * differently from the depth pass's, and a pixel left without its triangle has no normal. */
        if (fabs(dt_as_float(tile[k]) - z) <= 1e-6f * z) dt_atomic_min_u32(ids + k, triangle);
      } else {
        dt_atomic_min_u32(tile + k, dt_as_uint(z));
      }
    }
  }
}

DT_DEVICE_FN dt_point dt_project(dt_vec3 p, dt_camera cam) {
  const float inverse_z = 1.0f / p.z;
  dt_point s;
  s.u = dt_mul_add(cam.fx * p.x, inverse_z, cam.cx);
  s.v = dt_mul_add(cam.fy * p.y, inverse_z, cam.cy);
  return s;
}

/* Where edge (inside, outside) crosses z = near; computed from its inside end whichever way the
 * triangle runs, so that the triangles sharing a cut edge share the new vertex exactly. */
DT_DEVICE_FN dt_vec3 dt_cut(dt_vec3 inside, dt_vec3 outside, float near) {
  const float t = (near - inside.z) / (outside.z - inside.z);
  return dt_vec3_make(inside.x + (outside.x - inside.x) * t, inside.y + (outside.y - inside.y) * t, near);
}

/* Triangle abc (camera frame) that crosses z = near: cut there (Sutherland-Hodgman against one
 * plane, 3 or 4 vertices remain), then drawn as a fan (each part's rows from first_row, every row_step-th). */
DT_DEVICE_FN void dt_draw_cut_triangle(dt_vec3 a, dt_vec3 b, dt_vec3 c, dt_rigid pose, __global const float* planes,
                                       dt_camera cam, __global uint* tile, __global uint* ids, __global dt_u64* nearest,
                                       DT_LOCAL_PTR uint* local_tile, dt_pixel_box band, uint triangle, int first_row,
                                       int row_step) {
  const dt_vec3 p[3] = {a, b, c};
  dt_vec3 kept[4];
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const dt_vec3 from = p[i], to = p[i == 2 ? 0 : i + 1];
    const int from_in = from.z >= cam.near, to_in = to.z >= cam.near;
    if (from_in) kept[n++] = from;
    if (from_in != to_in) kept[n++] = from_in ? dt_cut(from, to, cam.near) : dt_cut(to, from, cam.near);
  }
  const dt_point first = dt_project(kept[0], cam);
  for (int i = 1; i + 1 < n; ++i)
    dt_raster_triangle_rows(first, dt_project(kept[i], cam), dt_project(kept[i + 1], cam), pose, planes, cam, tile,
                            ids, nearest, local_tile, band, triangle, first_row, 0x7fffffff, row_step);
}

/* Triangle t of the mesh placed by pose, cut at the near plane where it crosses it (tile, ids,
 * nearest and local_tile as for dt_raster_triangle_rows, t its triangle index): its rows from first_row, every
 * row_step-th (0 and 1: all of them). */
DT_DEVICE_FN void dt_draw_triangle_rows(dt_rigid pose, __global const float* vertices, __global const uint* triangles,
                                        __global const float* planes, uint t, dt_camera cam, __global uint* tile,
                                        __global uint* ids, __global dt_u64* nearest, DT_LOCAL_PTR uint* local_tile,
                                        dt_pixel_box band, int first_row, int row_step) {
  __global const uint* corners = triangles + 3 * DT_CAST(ulong, t);
  const dt_vec3 a = dt_vertex(pose, vertices, corners[0]), b = dt_vertex(pose, vertices, corners[1]),
                c = dt_vertex(pose, vertices, corners[2]);
  const int in_front = (a.z >= cam.near) + (b.z >= cam.near) + (c.z >= cam.near);
  if (in_front == 0) return;
  if (in_front == 3)
    dt_raster_triangle_rows(dt_project(a, cam), dt_project(b, cam), dt_project(c, cam), pose, planes, cam, tile, ids,
                            nearest, local_tile, band, t, first_row, 0x7fffffff, row_step);
  else
    dt_draw_cut_triangle(a, b, c, pose, planes, cam, tile, ids, nearest, local_tile, band, t, first_row, row_step);
}

/* The whole of triangle t (dt_draw_triangle_rows' every row). */
DT_DEVICE_FN void dt_draw_triangle(dt_rigid pose, __global const float* vertices, __global const uint* triangles,
                                   __global const float* planes, uint t, dt_camera cam, __global uint* tile,
                                   __global uint* ids, __global dt_u64* nearest, DT_LOCAL_PTR uint* local_tile,
                                   dt_pixel_box band) {
  dt_draw_triangle_rows(pose, vertices, triangles, planes, t, cam, tile, ids, nearest, local_tile, band, 0, 1);
}

/* The group's projected vertices (u, v of vertex i at 2i), kept by dt_pose_box where the mesh's
 * vertices fit in work-group memory: each vertex is a corner of about six triangles, and projecting it
 * once instead of once per corner is the same floats (the same dt_vertex and dt_project). */
DT_DEVICE_FN dt_point dt_point_at(DT_LOCAL_PTR const float* points, uint i) {
  dt_point p;
  p.u = points[2 * i];
  p.v = points[2 * i + 1];
  return p;
}

/* row_count rows from row `row` (counted from its first in band) of triangle t from the projected points,
 * when every vertex lies in front of the near plane (nothing is cut): those rows as dt_draw_triangle
 * draws them. */
DT_DEVICE_FN void dt_draw_projected_triangle_rows(DT_LOCAL_PTR const float* points, __global const uint* triangles,
                                                  uint t, uint row, uint row_count, dt_rigid pose,
                                                  __global const float* planes, dt_camera cam,
                                                  DT_LOCAL_PTR uint* local_tile, dt_pixel_box band) {
  __global const uint* corners = triangles + 3 * DT_CAST(ulong, t);
  dt_raster_triangle_rows(dt_point_at(points, corners[0]), dt_point_at(points, corners[1]),
                          dt_point_at(points, corners[2]), pose, planes, cam, 0, 0, 0, local_tile, band, t,
                          DT_CAST(int, row), DT_CAST(int, row_count), 1);
}

/* How many of band's rows the triangle of corners i0, i1, i2, from the projected points, may draw in (0:
 * none): dt_raster_triangle_rows' first tests (not degenerate, a pixel centre in its box) and its pixels within
 * the band's, on the same floats, so no triangle that draws is passed over and each row it draws is
 * counted. The caller loads the corners (render_weigh: the next triangle's while this one is tested). */
DT_DEVICE_FN uint dt_projected_triangle_rows(DT_LOCAL_PTR const float* points, uint i0, uint i1, uint i2,
                                             dt_camera cam, dt_pixel_box band) {
  const dt_point a = dt_point_at(points, i0), b = dt_point_at(points, i1), c = dt_point_at(points, i2);
  const float area = dt_edge_at(dt_make_edge(a, b), c.u, c.v);
  int u0, u1, v0, v1;
  if (!dt_drawn_facing(area, cam) || !dt_centre_range(a, b, c, cam, &u0, &u1, &v0, &v1)) return 0;
  u0 = max(u0, DT_CAST(int, band.u0));
  u1 = min(u1, DT_CAST(int, band.u0 + band.width) - 1);
  v0 = max(v0, DT_CAST(int, band.v0));
  v1 = min(v1, DT_CAST(int, band.v0 + band.height) - 1);
  if (u1 < u0 || v1 < v0) return 0;
  return DT_CAST(uint, v1 - v0 + 1);
}

/* The pixels a pose can cover: its projected vertices' bounding box, a pixel wider on each side (the
 * triangle passes project the same vertices, maybe contracted into FMAs differently), clamped to
 * the image; the whole image when a vertex lies before the near plane (cut triangles). With points
 * (room for vertex_count), the projections are kept there; *in_front says whether every vertex lies in
 * front of the near plane (only then are the points whole). */
DT_DEVICE_FN dt_pixel_box dt_pose_box(dt_rigid pose, __global const float* vertices, uint vertex_count, dt_camera cam,
                                      DT_LOCAL_PTR float* scratch, DT_LOCAL_PTR float* points, int* in_front) {
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
    if (points) {
      points[2 * i] = s.u;
      points[2 * i + 1] = s.v;
    }
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
  dt_pixel_box box = dt_box_make(0, 0, cam.width, cam.height);
  *in_front = scratch[4 * DT_GROUP_SIZE] == 0.0f;
  if (*in_front) {
    /* clamped in float before the conversion to int, as dt_raster_triangle_rows does */
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

/* vertices: 3 floats each, object frame; triangles: 3 vertex indices each; planes: object-frame
 * unit normal and offset (n . x = d) of each triangle. Group g draws particle first + g into tile g:
 * an atlas of fewer tiles than particles is drawn (and weighed) in turns (TrackerConfig::atlas_particles).
 * The atlas is written as the floats' bits. With
 * boxed, only the pose's box (dt_pose_box) of each tile is cleared and written, and the box goes to
 * boxes (4 per particle: u0, v0, width, height): the rest of the tile is left as it was, and whoever
 * reads the tile takes pixels outside the box as empty (weigh.cl, DeviceFilterProbe::last_atlas). At 640x480
 * the object's box is a few percent of the tile, which every frame was cleared, finished and read. */
__kernel DT_RESIDENCY void rasterize(__global const float* states, __global const float* vertices,
                                     __global const uint* triangles, __global const float* planes, uint triangle_count,
                                     uint vertex_count, dt_camera cam, dt_atlas_layout layout, __global uint* atlas,
                                     __global uint* boxes, uint boxed, uint first) {
  __local float scratch[5 * DT_GROUP_SIZE];
  const uint particle = first + get_group_id(0), lid = get_local_id(0);
  const dt_rigid pose = dt_particle_pose(states + DT_CAST(ulong, particle) * DT_STATE_STRIDE);
  /* dt_pose_box's barriers are met by every work-item whatever `boxed` says (PoCL faults on barriers
   * under a branch, even a uniform one). */
  int in_front;
  const dt_pixel_box pose_box = dt_pose_box(pose, vertices, vertex_count, cam, scratch, 0, &in_front);
  if (boxed && lid == 0) dt_box_store(boxes, particle, pose_box);
  const dt_pixel_box box = boxed ? pose_box : dt_box_make(0, 0, cam.width, cam.height);
  /* One tile per atlas row (particle-major, dt_atlas.h): the tile's pixels are contiguous, so plain
   * loops clear and finish it (stepping by rows of the page took 1.8 times as long on PoCL). */
  __global uint* tile = atlas + dt_atlas_tile_start(layout, get_group_id(0));
  const uint boxed_pixels = box.width * box.height;
  for (uint b = lid; b < boxed_pixels; b += DT_GROUP_SIZE) tile[dt_box_pixel(box, b, cam)] = DT_NO_SURFACE;
  barrier(CLK_GLOBAL_MEM_FENCE);

  for (uint t = lid; t < triangle_count; t += DT_GROUP_SIZE)
    dt_draw_triangle(pose, vertices, triangles, planes, t, cam, tile, 0, 0, 0, dt_no_band());
  barrier(CLK_GLOBAL_MEM_FENCE);

  for (uint b = lid; b < boxed_pixels; b += DT_GROUP_SIZE) {
    const uint k = dt_box_pixel(box, b, cam);
    if (tile[k] == DT_NO_SURFACE) tile[k] = 0u; /* 0.0f's bits */
  }
}
