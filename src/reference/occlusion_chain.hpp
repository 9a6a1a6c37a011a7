#pragma once
// Each pixel's occlusion is a two-state Markov chain in continuous time (MODEL.md): over dt
// seconds p relaxes towards p_inf = b / (1 - c) by the factor c^dt, c = a - b.
#include <cmath>
#include <depthtrack/tracker_config.hpp>

namespace depthtrack::reference {

inline double occlusion_steady_state(const OcclusionModel& m) {
  return m.p_visible_to_occluded / (1.0 - (m.p_occluded_stays - m.p_visible_to_occluded));
}

inline double propagate_occlusion(const OcclusionModel& m, double p, double dt) {
  const double c = m.p_occluded_stays - m.p_visible_to_occluded;
  const double p_inf = occlusion_steady_state(m);
  return p_inf + std::pow(c, dt) * (p - p_inf);
}

}  // namespace depthtrack::reference
