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

std::vector<TrackerConfig> fit_stages(const TrackerConfig& config) {
  std::vector<TrackerConfig> stages{fit_config(config)};
  if (config.refine.fine_noise_scale > 0) {
    TrackerConfig fine = config;
    fine.refine.noise_scale = config.refine.fine_noise_scale;
    stages.push_back(fit_config(fine));
  }
  return stages;
}

double step_tolerance(double noise_scale) {
  return 0.01 / (noise_scale * noise_scale);
}

double last_noise_scale(const Refinement& refine) {
  return refine.fine_noise_scale > 0 ? refine.fine_noise_scale : refine.noise_scale;
}

Eigen::Matrix<double, 6, 6> fit_covariance(const Eigen::Matrix<double, 6, 6>& h, int pixels, double radius,
                                           const Refinement& refine) {
  const double s = last_noise_scale(refine);
  return pose_covariance(h * (s * s), pixels, radius);
}

}  // namespace depthtrack::model
