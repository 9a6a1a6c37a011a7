#pragma once
// Two backends' fits from a common state take the same steps, but a decision at a threshold (a step's size at
// refine.converged_motion, a candidate's log-likelihood at the step tolerance) can go either way in float, and
// the fits then take different paths to the same optimum: one more step on one side, poses apart by more than
// the rounding of one path. Such fits are equivalent when the reference's own objective rates the device's
// pose as high as its own, within the step tolerance (what the fit itself counts as rounding), and the
// poses lie within one standard deviation of the fit's covariance of each other on every determined axis.
// A device test counts such a frame apart and starts the next one from the reference's state, as it does
// after a resampling tie.
#include <cmath>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker.hpp>

#include "filter/device_filter_probe.hpp"
#include "model/fit_noise.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/reference_filter.hpp"

namespace depthtrack::test {

// The same fit within float rounding: poses within 1e-5 m and 1e-4 rad, and the same steps tried.
inline bool same_fit(const Estimate& a, const Estimate& b) {
  return translation_error(a.pose, b.pose) <= 1e-5 && rotation_error(a.pose, b.pose) <= 1e-4 &&
         a.refine_iterations == b.refine_iterations;
}

// The device's whole state replaced by the reference's, so that the next frame starts from a common state
// (after a resampling tie, a silhouette pixel flipped, or fits equivalent but apart).
inline void restart_from_reference(DeviceFilter& device, const reference::ReferenceFilter& reference) {
  DeviceFilterProbe(device).set_state(reference.particles(), reference.occlusion_state(), reference.occlusion_times(),
                                      reference.log_weights());
}

struct FitComparison {
  double objective_gap = 0;  // the reference's objective at its pose minus at the device's (nats)
  double axis_d2 = 0;        // the largest (difference / standard deviation)^2 over the determined axes
};

// a: the reference's estimate of the frame it just fitted, b: the device's.
inline FitComparison compare_fits(const reference::ReferenceFilter& reference, const Estimate& a, const Estimate& b,
                                  const DepthImage& depth, const Mesh& mesh) {
  FitComparison c;
  c.objective_gap = reference.last_fit_objective(a.pose, depth) - reference.last_fit_objective(b.pose, depth);
  const auto apart = reference::twist_between(a.pose, b.pose, mesh.centre().cast<double>());
  for (int axis = 0; axis < 6; ++axis) {
    const double variance = a.covariance(axis, axis);
    if (std::isfinite(variance) && variance > 0) c.axis_d2 = std::max(c.axis_d2, apart[axis] * apart[axis] / variance);
  }
  return c;
}

inline bool equivalent_fits(const FitComparison& c, const TrackerConfig& config) {
  return std::abs(c.objective_gap) <= model::step_tolerance(model::last_noise_scale(config.refine)) && c.axis_d2 <= 1.0;
}

}  // namespace depthtrack::test
