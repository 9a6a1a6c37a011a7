#include "model/kernel_params.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "model/fit_noise.hpp"
#include "model/occlusion_chain.hpp"

namespace depthtrack::model {

dt_model model_params(const TrackerConfig& config) {
  const ObservationModel& o = config.observation;
  const OcclusionModel& oc = config.occlusion;
  return dt_model{static_cast<float>(o.sigma_constant),
                  static_cast<float>(o.sigma_quadratic),
                  static_cast<float>(o.tail_weight / o.max_depth),
                  static_cast<float>(1.0 - o.tail_weight),
                  static_cast<float>(o.occluder_rate),
                  static_cast<float>(std::log(oc.p_occluded_stays - oc.p_visible_to_occluded)),
                  static_cast<float>(occlusion_steady_state(oc))};
}

dt_motion motion_params(const MotionStep& step, const Eigen::Vector3d& centre) {
  return dt_motion{static_cast<float>(step.keep),        static_cast<float>(step.linear_std),
                   static_cast<float>(step.angular_std), static_cast<float>(step.dt),
                   static_cast<float>(centre.x()),       static_cast<float>(centre.y()),
                   static_cast<float>(centre.z())};
}

dt_initial initial_params(const InitialSpread& spread, const Eigen::Vector3d& centre, size_t mode_count) {
  return dt_initial{static_cast<float>(spread.metres), static_cast<float>(spread.radians),
                    static_cast<float>(centre.x()),    static_cast<float>(centre.y()),
                    static_cast<float>(centre.z()),    static_cast<dt_u32>(mode_count)};
}

dt_window window_params(const StateWindow& now, const StateWindow& last, const Camera& camera,
                        const TrackerConfig& config) {
  return dt_window{static_cast<dt_u32>(now.u0),       static_cast<dt_u32>(now.v0),
                   static_cast<dt_u32>(last.u0),      static_cast<dt_u32>(last.v0),
                   static_cast<dt_u32>(now.width),    static_cast<dt_u32>(now.height),
                   static_cast<dt_u32>(last.width),   static_cast<dt_u32>(last.height),
                   static_cast<dt_u32>(camera.width), static_cast<float>(fresh_occlusion(config))};
}

dt_camera camera_params(const Camera& camera, const TrackerConfig& config, bool cull_back_faces) {
  return dt_camera{static_cast<float>(camera.fx),
                   static_cast<float>(camera.fy),
                   static_cast<float>(camera.cx),
                   static_cast<float>(camera.cy),
                   static_cast<float>(config.near_plane),
                   static_cast<float>(config.observation.max_depth),
                   static_cast<dt_u32>(camera.width),
                   static_cast<dt_u32>(camera.height),
                   cull_back_faces ? 1u : 0u};
}

dt_refine_args refine_params(std::span<const TrackerConfig> stages, const Eigen::Vector3d& centre, double radius,
                             size_t vertex_count, double now, double dt, unsigned draw_slices) {
  if (stages.empty() || stages.size() > 2)
    throw std::invalid_argument("refine_params: the fit has one or two stages, not " + std::to_string(stages.size()));
  const Refinement& refine = stages.front().refine;
  const TrackerConfig& last = stages.back();
  return dt_refine_args{static_cast<float>(refine.damping),
                        static_cast<float>(refine.min_incidence),
                        static_cast<float>(centre.x()),
                        static_cast<float>(centre.y()),
                        static_cast<float>(centre.z()),
                        static_cast<float>(now),
                        static_cast<float>(dt),
                        refine.iterations,
                        static_cast<float>(radius),
                        static_cast<float>(refine.converged_motion),
                        static_cast<dt_u32>(vertex_count),
                        static_cast<float>(stages.front().loss.pixel_sigmas),
                        draw_slices,
                        static_cast<dt_u32>(stages.size()),
                        static_cast<float>(last.observation.sigma_constant),
                        static_cast<float>(last.observation.sigma_quadratic),
                        static_cast<float>(last.loss.pixel_sigmas),
                        static_cast<float>(step_tolerance(refine.noise_scale)),
                        static_cast<float>(step_tolerance(last.refine.noise_scale))};
}

std::string occlusion_definition(OcclusionStorage storage) {
  int code = DT_OCCLUSION_OFF;
  switch (storage) {
    case OcclusionStorage::PerPixelTime:
      code = DT_PER_PIXEL_TIME;
      break;
    case OcclusionStorage::GlobalTime:
      code = DT_GLOBAL_TIME;
      break;
    case OcclusionStorage::Off:
      code = DT_OCCLUSION_OFF;
      break;
  }
  return "DT_OCCLUSION=" + std::to_string(code);
}

float float_threshold(double threshold) {
  float f = static_cast<float>(threshold);
  if (static_cast<double>(f) > threshold) f = std::nextafter(f, -INFINITY);
  return f;
}

}  // namespace depthtrack::model
