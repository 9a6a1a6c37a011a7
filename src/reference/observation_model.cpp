#include "reference/observation_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace depthtrack::reference {

double depth_sigma(const ObservationModel& m, double y) {
  return m.sigma_constant + m.sigma_quadratic * y * y;
}

BandSide band_side(const ObservationModel& m, double pixel_sigmas, double y, double y_hat) {
  const double band = pixel_sigmas * depth_sigma(m, y);
  if (y < y_hat - band) return BandSide::Nearer;
  return y > y_hat + band ? BandSide::Behind : BandSide::Within;
}

ObservedDepth observed_depth(const ObservationModel& m, double y) {
  const double sigma = depth_sigma(m, y);
  const double tail = m.tail_weight / m.max_depth;
  const double keep = 1.0 - m.tail_weight;
  const double lambda = m.occluder_rate;
  // The exponential occluder prior on [0, infinity) convolved with the sensor's gaussian, what a pixel
  // without the object sees: lambda exp(exponent). exp overflows once sigma grows large (y beyond
  // ~250 m in double, ~150 m in float), so all three densities are stored divided by exp(log_scale):
  // ratios, log ratio and posterior keep their values, and the densities are exact while exponent <= 0.
  const double exponent = lambda * (0.5 * lambda * sigma * sigma - y);
  const double log_scale = std::max(0.0, exponent);
  const double scale = std::exp(-log_scale);
  ObservedDepth o;
  o.y = y;
  o.sigma = sigma;
  o.gaussian_norm = std::sqrt(2.0 * std::numbers::pi) * sigma;
  o.erfc_shift = lambda * sigma * sigma;
  o.erfc_width = std::numbers::sqrt2 * sigma;
  o.scale = scale;
  o.log_scale = log_scale;
  o.tail_scaled = tail * scale;
  o.background = keep * lambda * std::exp(exponent - log_scale);
  return o;
}

PixelDensities pixel_densities(const ObservationModel& m, double y, double y_hat) {
  return pixel_densities(m, observed_depth(m, y), y_hat);
}

}  // namespace depthtrack::reference
