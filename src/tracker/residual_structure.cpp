#include "tracker/residual_structure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "reference/observation_model.hpp"

namespace depthtrack {

ResidualStructure residual_structure(std::span<const float> rendered, const ObservationModel& model,
                                     double pixel_sigmas, const DepthImage& depth) {
  const int width = depth.width(), height = depth.height();
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> z(rendered.size(), kNone);  // NaN: not visible
  ResidualStructure r;
  double squares = 0;
  for (size_t k = 0; k < rendered.size(); ++k) {
    const double y_hat = rendered[k];
    const float y = depth.data()[k];
    if (y_hat <= 0 || !DepthImage::is_valid(y)) continue;
    if (reference::band_side(model, pixel_sigmas, y, y_hat) != reference::BandSide::Within) continue;
    z[k] = (y - y_hat) / reference::depth_sigma(model, y);
    squares += z[k] * z[k];
    ++r.pixels;
  }
  if (r.pixels == 0) return r;
  r.total = squares / r.pixels;
  double differences = 0;
  int pairs = 0;
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u);
      if (std::isnan(z[k])) continue;
      if (u + 1 < width && !std::isnan(z[k + 1])) {
        differences += (z[k] - z[k + 1]) * (z[k] - z[k + 1]);
        ++pairs;
      }
      const size_t below = k + static_cast<size_t>(width);
      if (v + 1 < height && !std::isnan(z[below])) {
        differences += (z[k] - z[below]) * (z[k] - z[below]);
        ++pairs;
      }
    }
  if (pairs > 0) r.white = std::min(r.total, differences / (2.0 * pairs));
  return r;
}

}  // namespace depthtrack
