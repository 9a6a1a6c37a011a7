/* Work-group sizes the host launches the filter's kernels with and builds their programs for
 * (DT_GROUP_SIZE): one place for the host (src/filter/frame_plan.hpp, src/atlas, src/filter/kernels) and
 * the kernels, which take DT_FILTER_GROUP where a program is built without DT_GROUP_SIZE. */
#ifndef DT_LAUNCH_H
#define DT_LAUNCH_H
/* Per particle, a group each: weigh, render_weigh, rasterize, score, the per-pixel fills; the wide
 * summary's groups; the one-group summary and prefix sum on a CPU. A power of two. */
#define DT_FILTER_GROUP 128
/* A work-item per particle: propagate, initialize, the resampling's gather. */
#define DT_LINEAR_GROUP 64
/* The one-group summary on a GPU: at most this many work-items (and the device's largest group). */
#define DT_SUMMARY_GPU_GROUP 512
/* The fit's groups (refine.cl, refine_spread.cl). */
#define DT_REFINE_GROUP 256
#endif
