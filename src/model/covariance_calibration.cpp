#include "model/covariance_calibration.hpp"

#include <algorithm>
#include <cmath>

namespace depthtrack::model {

Eigen::Matrix<double, 6, 6> calibrated_covariance(const Eigen::Matrix<double, 6, 6>& fit, double white, double smooth,
                                                  int pixels) {
  const double patches = std::max(1.0, static_cast<double>(pixels) / kSmoothPatches);
  const double scale =
      std::max(kMinResidualVariance, kWhiteScale * std::max(0.0, white) + std::max(0.0, smooth) * patches);
  Eigen::Matrix<double, 6, 6> covariance = fit;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (std::isfinite(fit(i, j))) covariance(i, j) = fit(i, j) * scale;
  return covariance;
}

}  // namespace depthtrack::model
