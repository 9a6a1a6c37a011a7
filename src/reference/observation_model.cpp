#include "reference/observation_model.hpp"

#include <cmath>
#include <numbers>

namespace depthtrack::reference {

double depth_sigma(const ObservationModel& m, double y) {
  return m.sigma_constant + m.sigma_quadratic * y * y;
}

PixelDensities pixel_densities(const ObservationModel& m, double y, double y_hat) {
  const double sigma = depth_sigma(m, y);
  const double tail = m.tail_weight / m.max_depth;
  const double lambda = m.occluder_rate;
  const double z = (y - y_hat) / sigma;
  const double gaussian = std::exp(-0.5 * z * z) / (std::sqrt(2.0 * std::numbers::pi) * sigma);
  // Exponential occluder prior on [0, y_hat] convolved with the sensor's gaussian.
  const double occluded = lambda * std::exp(lambda * (y_hat - y) + 0.5 * lambda * lambda * sigma * sigma) *
                          (1.0 + std::erf((y_hat - y + lambda * sigma * sigma) / (std::numbers::sqrt2 * sigma))) /
                          (2.0 * std::expm1(lambda * y_hat));
  // The same prior on [0, infinity): what a pixel without the object sees.
  const double background = lambda * std::exp(-lambda * y + 0.5 * lambda * lambda * sigma * sigma);
  const double keep = 1.0 - m.tail_weight;
  return {tail + keep * gaussian, tail + keep * occluded, tail + keep * background};
}

double pixel_log_ratio(const PixelDensities& d, double p) {
  return std::log(((1.0 - p) * d.visible + p * d.occluded) / d.background);
}

double occlusion_posterior(const PixelDensities& d, double p) {
  return p * d.occluded / ((1.0 - p) * d.visible + p * d.occluded);
}

}  // namespace depthtrack::reference
