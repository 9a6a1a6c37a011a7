/* The parameters kernels take by value, one struct per concept, compiled by the kernels (OpenCL C,
 * CUDA) and by the host, which builds each once from TrackerConfig (src/model/kernel_params.hpp,
 * where static_asserts pin sizes and offsets). Only 32-bit members, so every compiler lays them out
 * alike. The atlas layout is dt_atlas.h's dt_atlas_layout. */
#ifndef DT_PARAMS_H
#define DT_PARAMS_H
#include "dt_prelude.h"

/* The per-pixel observation model and the occlusion chain (MODEL.md), for dt_model.h. */
typedef struct {
  float sigma_constant, sigma_quadratic; /* sigma(y) = c + q y^2 */
  float tail_density;                    /* w / D */
  float keep;                            /* 1 - w */
  float lambda;                          /* occluder rate */
  float log_c;                           /* log(a - b) of the occlusion chain */
  float p_inf;                           /* its fixed point b / (1 - (a - b)) */
} dt_model;

/* One frame's motion step (propagate.cl): the constants of model::MotionStep. */
typedef struct {
  float keep;                         /* damping^(dt * rate) */
  float linear_std;                   /* m/s added per unit normal */
  float angular_std;                  /* rad/s added per unit normal */
  float dt;                           /* seconds */
  float centre_x, centre_y, centre_z; /* the mesh's centre, object frame */
} dt_motion;

/* The initial draw (initialize.cl): the spread, the mesh's centre (object frame), and how many
 * poses the cloud spreads around. */
typedef struct {
  float metres, radians;
  float centre_x, centre_y, centre_z;
  dt_u32 mode_count;
} dt_initial;

/* The working camera and clip range the rasterizer draws with (rasterize.cl), and whether it skips the
 * triangles facing away (1 where the mesh bounds a solid wound outward: core/mesh_topology.hpp). */
typedef struct {
  float fx, fy, cx, cy, near, far;
  dt_u32 width, height;
  dt_u32 cull_back_faces;
} dt_camera;

/* The pose refinement's settings and the mesh facts its stopping rule needs (refine.cl, refine_spread.cl). */
typedef struct {
  float damping;       /* Levenberg-Marquardt lambda on diag(H) */
  float min_incidence; /* pixels with |cos(normal, ray)| below it are left out of H */
  float centre_x, centre_y, centre_z;
  float now;              /* seconds since the first frame: the per-pixel-time occlusion mode ages p to it */
  float dt;               /* this frame's time step: the global-time occlusion mode ages p by it */
  int iterations;         /* damped steps at most */
  float radius;           /* largest vertex distance from the centre */
  float converged_motion; /* a step moving no mesh point farther than this (metres) is not tried */
  dt_u32 vertex_count;
  float pixel_sigmas; /* the confidence's band: a pixel within this many sigma of the surface is visible */
  dt_u32 draw_slices; /* work-items drawing each triangle, every draw_slices-th row each (DeviceRefiner) */
  dt_u32 stages;      /* 1, or 2: a second stage (Refinement::fine_noise_scale) with the fine_ values below */
  float fine_sigma_constant, fine_sigma_quadratic; /* the second stage's sigma(y), in place of dt_model's */
  float fine_pixel_sigmas;                         /* and its confidence band in its sigmas */
  float step_tolerance, fine_step_tolerance;       /* model::step_tolerance of each stage (nats) */
} dt_refine_args;

/* The occlusion state window (model::StateWindow, TrackerConfig::occlusion_window): each particle's
 * row of occlusion state holds width x height pixels from (u0, v0) this frame; the rows read (the
 * parents', from the last frame) hold last_width x last_height from (last_u0, last_v0) (an automatic
 * window grows between frames). A pixel outside this frame's window, or new to it, is fresh:
 * `initial` at time 0. image_width: the working image's, to place pixel k. */
typedef struct {
  dt_u32 u0, v0, last_u0, last_v0, width, height, last_width, last_height, image_width;
  float initial;
} dt_window;

/* How occlusion is stored, the value of the DT_OCCLUSION compile-time definition. */
#define DT_PER_PIXEL_TIME 0
#define DT_GLOBAL_TIME 1
#define DT_OCCLUSION_OFF 2
#endif
