#pragma once
// The kernels' by-value parameters (cl/dt_params.h), each built from the configuration by one
// function here, for the device filter, the kernel rasterizer and the pose scorer alike.
#include <cstddef>
#include <depthtrack/camera.hpp>
#include <depthtrack/initial_spread.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>
#include <string>

#include "dt_params.h"
#include "model/particle.hpp"
#include "model/state_window.hpp"

namespace depthtrack::model {

// The host's copies must be laid out as the kernels read them.
static_assert(sizeof(float) == 4 && sizeof(dt_u32) == 4);
static_assert(sizeof(dt_model) == 28 && offsetof(dt_model, keep) == 12 && offsetof(dt_model, p_inf) == 24);
static_assert(sizeof(dt_motion) == 28 && offsetof(dt_motion, dt) == 12 && offsetof(dt_motion, centre_z) == 24);
static_assert(sizeof(dt_initial) == 24 && offsetof(dt_initial, centre_x) == 8 &&
              offsetof(dt_initial, mode_count) == 20);
static_assert(sizeof(dt_camera) == 36 && offsetof(dt_camera, far) == 20 && offsetof(dt_camera, height) == 28 &&
              offsetof(dt_camera, cull_back_faces) == 32);
static_assert(sizeof(dt_refine_args) == 76 && offsetof(dt_refine_args, dt) == 24 &&
              offsetof(dt_refine_args, iterations) == 28 && offsetof(dt_refine_args, vertex_count) == 40 &&
              offsetof(dt_refine_args, pixel_sigmas) == 44 && offsetof(dt_refine_args, draw_slices) == 48 &&
              offsetof(dt_refine_args, stages) == 52 && offsetof(dt_refine_args, fine_pixel_sigmas) == 64 &&
              offsetof(dt_refine_args, fine_step_tolerance) == 72);
static_assert(sizeof(dt_window) == 40 && offsetof(dt_window, image_width) == 32 && offsetof(dt_window, initial) == 36);

// Observation model and occlusion chain of config.
dt_model model_params(const TrackerConfig& config);
// One frame's motion step about the mesh's centre (object frame).
dt_motion motion_params(const MotionStep& step, const Eigen::Vector3d& centre);
// The initial draw around mode_count poses.
dt_initial initial_params(const InitialSpread& spread, const Eigen::Vector3d& centre, size_t mode_count);
// The state window this frame (now) and the rows read (last), with the fresh occlusion probability.
dt_window window_params(const StateWindow& now, const StateWindow& last, const Camera& camera,
                        const TrackerConfig& config);
// The working camera with the configuration's near plane and the model's far limit; cull_back_faces where
// the mesh drawn bounds a solid wound outward (MeshBuffers::cull_back_faces).
dt_camera camera_params(const Camera& camera, const TrackerConfig& config, bool cull_back_faces);
// The kernels' DT_OCCLUSION definition for the storage mode, "DT_OCCLUSION=<DT_PER_PIXEL_TIME...>".
std::string occlusion_definition(OcclusionStorage storage);
// The refinement's settings for its stages (model::fit_stages: one or two) and a mesh with this centre
// (object frame), radius and vertex count, at `now` seconds since the first frame, `dt` after the frame
// before; draw_slices: the work-items drawing each triangle (DeviceRefiner). The first stage's sigma(y)
// reaches the kernels through model_params(stages[0]), the second's through the fine_ fields.
dt_refine_args refine_params(std::span<const TrackerConfig> stages, const Eigen::Vector3d& centre, double radius,
                             size_t vertex_count, double now, double dt, unsigned draw_slices);
// The largest float not above threshold: a float x exceeds it exactly when x exceeds threshold, so a
// float comparison on the device decides as the double comparison on the host.
float float_threshold(double threshold);

}  // namespace depthtrack::model
