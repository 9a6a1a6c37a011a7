#include "model/covariance_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace depthtrack::model {

Eigen::Matrix<double, 6, 6> calibrated_covariance(const Eigen::Matrix<double, 6, 6>& fit, double white, double smooth,
                                                  int pixels, int width) {
  const double patches = std::max(1.0, static_cast<double>(pixels) / kSmoothPatches);
  const double resolution = std::sqrt(kReferenceWidth / std::max(1, width));
  const double scale = std::max(kMinResidualVariance,
                                (kWhiteScale * std::max(0.0, white) + std::max(0.0, smooth) * patches) * resolution);
  Eigen::Matrix<double, 6, 6> covariance = fit;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (std::isfinite(fit(i, j))) covariance(i, j) = fit(i, j) * scale;
  return covariance;
}

Eigen::Matrix<double, 6, 6> with_principal_point(const Eigen::Matrix<double, 6, 6>& covariance, double depth,
                                                 double focal) {
  const double shift = kPrincipalPointPixels * depth / focal;
  Eigen::Matrix<double, 6, 6> c = covariance;
  for (int i = 0; i < 2; ++i)
    if (std::isfinite(c(i, i))) c(i, i) += shift * shift;
  return c;
}

Eigen::Matrix<double, 6, 6> with_undetermined_direction(const Eigen::Matrix<double, 6, 6>& covariance,
                                                        const Eigen::Matrix<double, 6, 1>& direction) {
  if (covariance.array().isNaN().any()) return covariance;
  Eigen::Matrix<double, 6, 1> finite = direction;
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(covariance(i, i))) finite(i) = 0;
  if (!(finite.norm() >= 0.1 * direction.norm()) || finite.norm() == 0) return covariance;
  finite.normalize();
  Eigen::Matrix<double, 6, 6> c = covariance;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (std::isfinite(c(i, i)) && std::isfinite(c(j, j))) c(i, j) += kUndeterminedVariance * finite(i) * finite(j);
  return c;
}

Eigen::Matrix<double, 6, 6> undetermined_covariance() {
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  c.diagonal().setConstant(std::numeric_limits<double>::infinity());
  return c;
}

}  // namespace depthtrack::model
