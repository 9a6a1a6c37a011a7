/* render_weigh.cl's list of the triangles to draw, a chunk at a time, each with its first row's place, and
 * the tally one atomic add advances: (triangles << DT_ROW_BITS) | rows. Shared with the host that counts
 * the list's work-group memory (render_weigh_layout, src/filter/frame_plan.cpp). 512 triangles a chunk rather than 256
 * halves the chunks' barriers; with the corners loaded ahead, the handset's frame at 1,000,000 particles
 * took 18.2 / 18.3 ms on the H100 instead of 19.3 / 19.4 (CUDA / NVIDIA OpenCL; the
 * mug's weigh level). */
#ifndef DT_DRAW_LIST_H
#define DT_DRAW_LIST_H
#define DT_DRAW_LIST 512u
#define DT_ROW_BITS 22u /* room for a tally of DT_DRAW_LIST triangles above the rows */
#define DT_ROW_MASK ((1u << DT_ROW_BITS) - 1u)
#endif
