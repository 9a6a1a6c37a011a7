/* Layout of one particle's kinematic state in device memory: DT_STATE_STRIDE floats per particle. */
#ifndef DT_STATE_H
#define DT_STATE_H
#define DT_TX 0  /* translation, metres (camera_from_object) */
#define DT_QW 3  /* rotation quaternion w, x, y, z */
#define DT_VX 7  /* linear velocity, m/s, object's local frame */
#define DT_WX 10 /* angular velocity, rad/s, object's local frame */
#define DT_STATE_STRIDE 16

/* The estimate a frame produces (one small buffer the host reads back). */
#define DT_EST_TX 0
#define DT_EST_QW 3
#define DT_EST_VX 7
#define DT_EST_WX 10
#define DT_EST_ESS 13
#define DT_EST_KL 14
#define DT_EST_MAX_LL 15
#define DT_EST_MEAN_LL 16
#define DT_EST_HEAVIEST 17 /* index of the heaviest particle, its bits stored as a float (summarize.cl) */
#define DT_EST_RESAMPLE 18 /* 1 when the KL from uniform exceeds the threshold, else 0 (summarize.cl) */
#define DT_EST_REFINE_ITERATIONS 19 /* steps the refinement tried (refine.cl) */
/* The fit's H at the refined pose, its lower triangle row by row (21 floats), from which the host makes the
 * covariance (model::pose_covariance). */
#define DT_EST_NORMAL 20
#define DT_EST_FIT_PIXELS 41 /* the pixels in that H (dt_refine_state.h's DT_REFINE_PIXELS) */
#define DT_EST_VISIBLE 42    /* the refined pose's confidence counts (DT_REFINE_VISIBLE) */
#define DT_EST_MEASURED 43   /* and DT_REFINE_MEASURED */
#define DT_EST_SIZE 44
#endif
