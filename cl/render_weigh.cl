/* The kernel renderer's rasterization and weigh in one kernel: a work-group per particle draws its
 * tile into work-group memory (rasterize.cl's drawing, its atomic min on local memory) and weighs it
 * from there (dt_weigh.h, as weigh.cl), so the atlas never goes through device memory: per pixel and
 * particle that saves the tile's clear, its atomics in global memory, its finishing pass and weigh's
 * read of it. The same depths and, over the same rectangle (the pose's box, which boxed rasterize.cl
 * keeps, and the state window), the same sums in the same order as rasterize.cl + weigh.cl (the
 * atomic minimum does not depend on the order the triangles come in). With keep_atlas the tile is also
 * stored in the atlas (particle-major, as rasterize.cl writes it), for tests that compare it. With
 * propagate, in a program compiled with DT_PROPAGATE_INSIDE=1 (small clouds: the host's
 * kFusedLaunchParticles), the group first moves its particle by the frame's motion step (dt_propagate.h,
 * what propagate.cl does; the frame then launches one kernel fewer); without the define the block is
 * left out, as it costs NVRTC's register allocation spills.
 * Compile-time choices: DT_GROUP_SIZE (power of two), DT_OCCLUSION as weigh.cl, DT_TILE_PIXELS the
 * pixels the tile in work-group memory holds (at least a row of the image; a pose's box beyond it is
 * drawn and weighed in bands of rows; the host uses this kernel only where the whole image would fit),
 * DT_SHARED_POINTS the vertices whose projections the group keeps in work-group memory (the mesh's
 * vertex count where they fit, else 0: each triangle then projects its own corners), DT_RESIDENT_GROUPS the
 * groups each compute unit should hold at once (CUDA's __launch_bounds__ through DT_RESIDENCY; 0: no hint).
 * Reference: Rasterizer::render and ReferenceFilter::weigh_particle. */
#include "rasterize.cl"
#include "dt_draw_list.h"
#include "dt_propagate.h"
#include "dt_weigh.h"

#ifndef DT_PROPAGATE_INSIDE
#define DT_PROPAGATE_INSIDE 0
#endif

__kernel DT_RESIDENCY void render_weigh(__global float* states, __global const float* vertices,
                                        __global const uint* triangles, __global const float* planes,
                                        uint triangle_count, uint vertex_count, dt_camera cam,
                                        __global const float* observed, __global const uint* parents,
                                        __global const float* occlusion_from, __global const dt_u16* time_from,
                                        __global float* occlusion_to, __global dt_u16* time_to,
                                        __global float* frame_times, __global float* log_likelihood,
                                        __global float* log_weight, dt_model m, float now, uint now_index, float dt,
                                        __global uint* atlas, uint keep_atlas, dt_window win, uint propagate,
                                        uint seed_lo, uint seed_hi, uint frame, dt_motion motion) {
  __local uint tile[DT_TILE_PIXELS];
  __local float scratch[5 * DT_GROUP_SIZE]; /* dt_pose_box's reduction, then the group sum */
#if DT_SHARED_POINTS > 0
  __local float points[2 * DT_SHARED_POINTS]; /* the pose's projected vertices */
  __local uint listed[DT_DRAW_LIST];          /* triangles to draw, a chunk at a time */
  __local uint first_row[DT_DRAW_LIST];       /* the place of each one's first row among the chunk's */
  __local uint listed_tally;                  /* (triangles << DT_ROW_BITS) | rows, as listed so far */
#endif
  const uint particle = get_group_id(0), lid = get_local_id(0), pixels = cam.width * cam.height;
  dt_weigh_begin(frame_times, now, now_index);
#if DT_PROPAGATE_INSIDE
  if (propagate) { /* a kernel argument: every work-item meets the barrier */
    if (lid == 0) dt_propagate_particle(states, particle, seed_lo, seed_hi, frame, motion);
    barrier(CLK_GLOBAL_MEM_FENCE);
  }
#endif
  /* Only the pose's box is cleared, drawn and weighed (no triangle draws outside it), with the state
   * window's pixels, whose state moves from the parent's row to the particle's own. */
  const dt_rigid pose = dt_particle_pose(states + DT_CAST(ulong, particle) * DT_STATE_STRIDE);
#if DT_SHARED_POINTS > 0
  /* The host sizes it to the mesh; another mesh draws as below. */
  DT_LOCAL_PTR float* const kept = vertex_count <= DT_SHARED_POINTS ? points : 0;
#else
  DT_LOCAL_PTR float* const kept = 0;
#endif
  int in_front;
  const dt_pixel_box box = dt_pose_box(pose, vertices, vertex_count, cam, scratch, kept, &in_front);
  const int projected = kept != 0 && in_front;
  if (keep_atlas) /* tests: the whole tile, 0.0f's bits outside the box (the bands below write the box) */
    for (uint k = lid; k < pixels; k += DT_GROUP_SIZE)
      if (!dt_box_holds(box, k % cam.width, k / cam.width)) atlas[DT_CAST(ulong, particle) * pixels + k] = 0u;
  const ulong from = DT_CAST(ulong, parents[particle]) * dt_window_last_row(win),
              to = DT_CAST(ulong, particle) * dt_window_row(win);
  const dt_pixel_box visited = dt_weigh_box(box, win);
  const uint visits = visited.width * visited.height;
  /* The box drawn and weighed in bands of its rows, as many as the tile holds (the host makes it hold a
   * row of the image): one band, the whole box, unless the pose covers more pixels than that. Each band
   * weighs the visited rectangle's rows up to its own last (the last band: all that are left), so each
   * work-item still adds its pixels in the rectangle's order, as one pass over the whole image would. */
  const uint band_rows = box.width > 0 ? DT_TILE_PIXELS / box.width : 0, box_end = box.v0 + box.height;
  float sum = 0.0f;
  uint weighed = 0; /* the visited rectangle's pixels before this band's rows */
  /* As many bands as the widest box can need: a count from kernel arguments, so that every work-item
   * meets every barrier (PoCL faults on barriers that a value from memory decides on); a band after the
   * box's last is empty and weighs nothing. */
  const uint most_bands = (cam.height + DT_TILE_PIXELS / cam.width - 1) / (DT_TILE_PIXELS / cam.width);
  for (uint band_index = 0; band_index < most_bands; ++band_index) {
    const uint v0 = box.v0 + band_index * band_rows;
    const uint rows = band_rows > 0 && v0 < box_end ? min(band_rows, box_end - v0) : 0;
    const dt_pixel_box band = dt_box_make(box.u0, v0, box.width, rows);
    const int last = band_rows == 0 || v0 + rows >= box_end;
    for (uint b = lid; b < band.width * band.height; b += DT_GROUP_SIZE) tile[b] = DT_NO_SURFACE;
    barrier(CLK_LOCAL_MEM_FENCE);
#if DT_SHARED_POINTS > 0
    /* Every vertex in front (the usual case): the triangles that hold a pixel centre in the band (few of
     * a fine mesh's; which, and how many for each work-item, vary) are listed from the projected points
     * with their rows, then the rows are drawn by the work-items in turn, so a group does not wait at the
     * barrier for the work-item that drew the most (on the H200 most of the kernel's stalls; a coarse
     * mesh's large triangles, drawn whole by one work-item each, left most of a group waiting). One
     * atomic add gives a triangle its place in the list and its first row's place among the rows, so
     * both rise together and a row finds its triangle by bisection. The chunk loop's bounds are kernel
     * arguments, so every work-item meets every barrier (PoCL faults on barriers that a value from
     * memory decides on). Every triangle that draws is listed, even one of a single candidate pixel: drawn
     * where it was found instead, the group's rows waited on the work-items that found the most (H100,
     * the mug's weigh 240 -> 195 us listed). A work-item's triangles follow one
     * another through the chunks, and each one's corners are loaded while the one before it is tested (the
     * next chunk's first while this chunk's rows are drawn): waiting for those loads was a sixth of the
     * mug's stalls (Nsight Compute, H100). */
    uint next0 = 0, next1 = 0, next2 = 0; /* the corners of this work-item's next triangle */
    if (projected && lid < triangle_count) {
      next0 = triangles[3 * lid];
      next1 = triangles[3 * lid + 1];
      next2 = triangles[3 * lid + 2];
    }
    for (uint first = 0; first < triangle_count; first += DT_DRAW_LIST) {
      if (lid == 0) listed_tally = 0;
      barrier(CLK_LOCAL_MEM_FENCE);
      const uint end = triangle_count - first < DT_DRAW_LIST ? triangle_count : first + DT_DRAW_LIST;
      if (projected)
        for (uint t = first + lid; t < end; t += DT_GROUP_SIZE) {
          const uint i0 = next0, i1 = next1, i2 = next2;
          uint following = t + DT_GROUP_SIZE; /* this work-item's next triangle, in this chunk or the next */
          if (following >= first + DT_DRAW_LIST) following = first + DT_DRAW_LIST + lid;
          if (following < triangle_count) {
            __global const uint* corners = triangles + 3 * DT_CAST(ulong, following);
            next0 = corners[0];
            next1 = corners[1];
            next2 = corners[2];
          }
          const uint rows = dt_projected_triangle_rows(points, i0, i1, i2, cam, band);
          if (rows > 0) {
            const uint before = dt_atomic_add_local_u32(&listed_tally, (1u << DT_ROW_BITS) | rows);
            listed[before >> DT_ROW_BITS] = t;
            first_row[before >> DT_ROW_BITS] = before & DT_ROW_MASK;
          }
        }
      barrier(CLK_LOCAL_MEM_FENCE);
      const uint tally = listed_tally, count = tally >> DT_ROW_BITS, rows = tally & DT_ROW_MASK;
      for (uint r = lid; r < rows; r += DT_GROUP_SIZE) {
        uint low = 0, high = count; /* the last triangle whose first row is at or before row r */
        while (high - low > 1) {
          const uint middle = (low + high) / 2;
          if (first_row[middle] <= r)
            low = middle;
          else
            high = middle;
        }
        dt_draw_projected_triangle_rows(points, triangles, listed[low], r - first_row[low], 1, pose, planes, cam, tile,
                                        band);
      }
      barrier(CLK_LOCAL_MEM_FENCE);
    }
#endif
    if (!projected) /* each triangle projects its own corners, and is cut where it crosses the near plane */
      for (uint t = lid; t < triangle_count; t += DT_GROUP_SIZE)
        dt_draw_triangle(pose, vertices, triangles, planes, t, cam, 0, 0, 0, tile, band);
    barrier(CLK_LOCAL_MEM_FENCE);

    if (keep_atlas) /* tests: the band's pixels, 0.0f's bits where nothing was drawn */
      for (uint b = lid; b < band.width * band.height; b += DT_GROUP_SIZE)
        atlas[DT_CAST(ulong, particle) * pixels + dt_box_pixel(band, b, cam)] = tile[b] != DT_NO_SURFACE ? tile[b] : 0u;
    /* The visited rectangle's pixels to the work-items in turn (pixel b to work-item b mod the group's
     * size), as the whole image's in a plain loop. */
    const uint until = last ? visits : (v0 + rows - visited.v0) * visited.width;
    uint b = weighed + ((lid - weighed) & (DT_GROUP_SIZE - 1));
    dt_u32 x = 0, y = 0;
    if (b < until) dt_pixel_place(b, visited.width, &x, &y);
    for (; b < until; b += DT_GROUP_SIZE, dt_pixel_step(visited.width, &x, &y)) {
      const dt_u32 u = visited.u0 + x, v = visited.v0 + y;
      const uint k = v * cam.width + u;
      const uint at = (v - band.v0) * band.width + (u - band.u0);
      const uint bits = dt_box_holds(band, u, v) && tile[at] != DT_NO_SURFACE ? tile[at] : 0u; /* 0.0f where undrawn */
      sum += dt_weigh_image_pixel(k, u, v, dt_as_float(bits), observed, win, from, to, occlusion_from, time_from,
                                  occlusion_to, time_to, frame_times, m, now, now_index, dt);
    }
    weighed = until;
    barrier(CLK_LOCAL_MEM_FENCE); /* the next band's clear overwrites the tile */
  }
  dt_weigh_end(scratch, sum, log_likelihood, log_weight, particle);
}
