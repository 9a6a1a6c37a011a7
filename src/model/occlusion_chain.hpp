#pragma once
// Each pixel's occlusion is a two-state Markov chain in continuous time (MODEL.md): over dt
// seconds p relaxes towards p_inf = b / (1 - c) by the factor c^dt, c = a - b.
#include <cmath>
#include <depthtrack/tracker_config.hpp>

namespace depthtrack::model {

inline double occlusion_steady_state(const OcclusionModel& m) {
  return m.p_visible_to_occluded / (1.0 - (m.p_occluded_stays - m.p_visible_to_occluded));
}

inline double propagate_occlusion(const OcclusionModel& m, double p, double dt) {
  const double c = m.p_occluded_stays - m.p_visible_to_occluded;
  const double p_inf = occlusion_steady_state(m);
  return p_inf + std::pow(c, dt) * (p - p_inf);
}

// The occlusion probability a fresh particle's pixels hold: occlusion.initial, or 0 when occlusion
// modelling is off.
inline double fresh_occlusion(const TrackerConfig& config) {
  return config.occlusion_storage == OcclusionStorage::Off ? 0.0 : config.occlusion.initial;
}

}  // namespace depthtrack::model
