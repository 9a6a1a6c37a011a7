/* The pose refinement's sums and, for its spread layout (refine_spread.cl), the fit's state between
 * kernels: one small device buffer, sized by the host from this struct. Only 32-bit members. */
#ifndef DT_REFINE_STATE_H
#define DT_REFINE_STATE_H
#include "dt_params.h"
#include "dt_prelude.h"
#include "dt_state.h"

#define DT_REFINE_SUMS 31 /* H's lower triangle (21), g (6), objective, pixels, visible, measured */
#define DT_REFINE_OBJECTIVE 27
#define DT_REFINE_PIXELS 28
/* The confidence's counts (TrackSupervisor's silhouette shares): covered pixels with a valid depth,
 * and those of them within pixel_sigmas sigma of the surface. */
#define DT_REFINE_VISIBLE 29
#define DT_REFINE_MEASURED 30
/* The spread layout's buffers (refine_spread.cl), also filled by the host: a pixel's (depth bits << 32)
 * | triangle with nothing drawn (+inf's bits, no triangle), and a partial row's (stamp << 32) | bits
 * before any group wrote it (a stamp no evaluation has). */
#define DT_NEAREST_EMPTY DT_CAST(dt_u64, 0x7f800000ffffffff)
#define DT_ROW_UNWRITTEN DT_CAST(dt_u64, 0xffffffff00000000)

typedef struct {
  dt_u32 active;     /* 1 while a candidate waits to be evaluated */
  dt_u32 stage;      /* the stage being fitted (0, then 1 with dt_refine_args.stages 2) */
  dt_u32 evaluation; /* evaluations judged in this stage */
  dt_u32 arrived;    /* the sums kernel's groups done with this evaluation (the last one judges it) */
  dt_u32 stamp;      /* evaluations summed since the fit state was made: tags the partial rows */
  int tried;         /* steps tried (candidates after the start) */
  float lambda;
  float candidate[DT_STATE_STRIDE]; /* dt_state.h's layout (pose only) */
  float best[DT_STATE_STRIDE];      /* the best pose evaluated */
  float best_sums[DT_REFINE_SUMS];  /* its normal equations */
  /* The frame's settings, which change every frame (the time, the state window): set by refine_begin
   * alone, so the draws' and sums' arguments stay the same from frame to frame (a CUDA graph replays
   * them without setting any). */
  dt_refine_args args;
  dt_window win;
} dt_refine_state;
#endif
