#pragma once
// The pose refinement's own depth noise (Refinement::noise_scale): every backend's fit is built from
// fit_config(config), so that the reference and the devices fit the same likelihood, and hands its H to
// fit_covariance, so that the covariance is the filter's noise's.
#include <Eigen/Core>
#include <depthtrack/tracker_config.hpp>
#include <vector>

namespace depthtrack::model {

// config with sigma(y) scaled by refine.noise_scale for the fit's weights and objective, and
// loss.pixel_sigmas by its inverse, so that the confidence's band (pixel_sigmas sigma(y), counted by the
// fit) keeps its width in metres.
TrackerConfig fit_config(const TrackerConfig& config);

// The fit's stages, coarse to fine: fit_config(config), then, with refine.fine_noise_scale > 0, the
// second stage's (fit_config at that noise). Every backend fits these.
std::vector<TrackerConfig> fit_stages(const TrackerConfig& config);

// How far a step of the fit may lower its log-likelihood and still be kept (nats), at the stage's noise
// (Refinement::noise_scale s): 0.01 / s^2. Near the optimum steps change the objective by less than
// float rounding does, so a strict comparison would let the float device and the double reference
// decide differently and end a step apart; the rounding grows as 1 / s^2 (each pixel's term is
// (y - y_hat)^2 / (s sigma)^2), and so does the tolerance. Both the reference and the kernels use it.
double step_tolerance(double noise_scale);

// The noise the fit's last stage weighs with: refine.fine_noise_scale when set, else noise_scale.
double last_noise_scale(const Refinement& refine);

// The covariance of the fit's last stage's H at the filter's sigma(y): H scaled by s^2, s =
// last_noise_scale(refine) (the stage's weights are 1 / (s sigma)^2), then model::pose_covariance.
Eigen::Matrix<double, 6, 6> fit_covariance(const Eigen::Matrix<double, 6, 6>& h, int pixels, double radius,
                                           const Refinement& refine);

}  // namespace depthtrack::model
