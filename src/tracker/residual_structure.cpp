#include "tracker/residual_structure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "reference/observation_model.hpp"

namespace depthtrack {

ResidualStructure residual_structure(std::span<const float> rendered, const ObservationModel& model,
                                     double pixel_sigmas, const DepthImage& depth) {
  const int width = depth.width(), height = depth.height();
  // The normalized residual at pixel k, NaN where the pose is not seen there. Computed where it is
  // read (each pixel up to three times) instead of into a frame-sized buffer.
  const auto residual = [&](size_t k) {
    const double y_hat = rendered[k];
    const float y = depth.data()[k];
    if (y_hat <= 0 || !DepthImage::is_valid(y)) return std::numeric_limits<double>::quiet_NaN();
    if (reference::band_side(model, pixel_sigmas, y, y_hat) != reference::BandSide::Within)
      return std::numeric_limits<double>::quiet_NaN();
    return (y - y_hat) / reference::depth_sigma(model, y);
  };
  ResidualStructure r;
  double squares = 0, differences = 0;
  int pairs = 0;
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u);
      const double z = residual(k);
      if (std::isnan(z)) continue;
      squares += z * z;
      ++r.pixels;
      if (u + 1 < width) {
        const double right = residual(k + 1);
        if (!std::isnan(right)) {
          differences += (z - right) * (z - right);
          ++pairs;
        }
      }
      if (v + 1 < height) {
        const double below = residual(k + static_cast<size_t>(width));
        if (!std::isnan(below)) {
          differences += (z - below) * (z - below);
          ++pairs;
        }
      }
    }
  if (r.pixels == 0) return r;
  r.total = squares / r.pixels;
  if (pairs > 0) r.white = std::min(r.total, differences / (2.0 * pairs));
  return r;
}

}  // namespace depthtrack
