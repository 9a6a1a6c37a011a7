#pragma once
// The observation and occlusion model as the kernels take it by value (cl/dt_model.h's dt_model).
#include <cmath>
#include <depthtrack/tracker_config.hpp>

#include "reference/occlusion_chain.hpp"

namespace depthtrack {

struct ModelArgs {
  float sigma_constant, sigma_quadratic, tail_density, keep, lambda, log_c, p_inf;
};

inline ModelArgs model_args(const TrackerConfig& config) {
  const ObservationModel& o = config.observation;
  const OcclusionModel& oc = config.occlusion;
  return ModelArgs{static_cast<float>(o.sigma_constant),
                   static_cast<float>(o.sigma_quadratic),
                   static_cast<float>(o.tail_weight / o.max_depth),
                   static_cast<float>(1.0 - o.tail_weight),
                   static_cast<float>(o.occluder_rate),
                   static_cast<float>(std::log(oc.p_occluded_stays - oc.p_visible_to_occluded)),
                   static_cast<float>(reference::occlusion_steady_state(oc))};
}

}  // namespace depthtrack
