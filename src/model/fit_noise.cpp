#include "model/fit_noise.hpp"

#include "model/pose_covariance.hpp"

namespace depthtrack::model {

TrackerConfig fit_config(const TrackerConfig& config) {
  TrackerConfig fit = config;
  const double s = config.refine.noise_scale;
  fit.observation.sigma_constant *= s;
  fit.observation.sigma_quadratic *= s;
  fit.loss.pixel_sigmas /= s;
  return fit;
}

Eigen::Matrix<double, 6, 6> fit_covariance(const Eigen::Matrix<double, 6, 6>& h, int pixels, double radius,
                                           const Refinement& refine) {
  return pose_covariance(h * (refine.noise_scale * refine.noise_scale), pixels, radius);
}

}  // namespace depthtrack::model
