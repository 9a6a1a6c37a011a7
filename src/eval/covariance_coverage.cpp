#include "eval/covariance_coverage.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <depthtrack/error.hpp>
#include <string>

#include "model/covariance_calibration.hpp"

namespace depthtrack {

Eigen::Matrix<double, 6, 1> pose_error_twist(const Pose& estimate, const Pose& truth, const Eigen::Vector3d& centre) {
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() = estimate.apply(centre) - truth.apply(centre);
  e.tail<3>() = rotation_log(estimate.rotation * truth.rotation.conjugate());
  return e;
}

double chi2_95(int dof) {
  static constexpr double kQuantile[6] = {3.841458821, 5.991464547,  7.814727903,
                                          9.487729037, 11.070497694, 12.591587244};
  if (dof < 1 || dof > 6) throw InputError("chi2_95: degrees of freedom must be 1 to 6, got " + std::to_string(dof));
  return kQuantile[dof - 1];
}

std::optional<CovarianceCheck> check_covariance(const Eigen::Matrix<double, 6, 1>& error,
                                                const Eigen::Matrix<double, 6, 6>& covariance) {
  if (covariance.array().isNaN().any() || !error.allFinite()) return std::nullopt;
  int axes[6], n = 0;
  for (int i = 0; i < 6; ++i)
    if (std::isfinite(covariance(i, i))) axes[n++] = i;
  if (n == 0) return std::nullopt;
  Eigen::MatrixXd block(n, n);
  Eigen::VectorXd e(n);
  for (int i = 0; i < n; ++i) {
    e(i) = error(axes[i]);
    for (int j = 0; j < n; ++j) block(i, j) = covariance(axes[i], axes[j]);
  }
  // Over the block's principal directions, those with a variance of kDeterminedBelow or more left out
  // (a turn about a tilted axis of symmetry).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(block);
  if (eigen.info() != Eigen::Success || !(eigen.eigenvalues().minCoeff() > 0)) return std::nullopt;
  const Eigen::VectorXd along = eigen.eigenvectors().transpose() * e;
  CovarianceCheck check;
  for (int i = 0; i < n; ++i) {
    if (eigen.eigenvalues()(i) >= model::kDeterminedBelow) continue;
    check.d2 += along(i) * along(i) / eigen.eigenvalues()(i);
    ++check.dof;
  }
  if (check.dof == 0) return std::nullopt;
  check.inside = check.d2 <= chi2_95(check.dof);
  for (int i = 0; i < n; ++i)
    if (block(i, i) < model::kDeterminedBelow) check.axis_d2[static_cast<size_t>(axes[i])] = e(i) * e(i) / block(i, i);
  return check;
}

Coverage coverage(const std::vector<CovarianceCheck>& checks, size_t no_region) {
  Coverage c;
  c.checked = checks.size();
  c.no_region = no_region;
  for (const CovarianceCheck& check : checks) c.inside += check.inside;
  if (c.checked == 0) return c;
  const double n = static_cast<double>(c.checked), p = static_cast<double>(c.inside) / n, z = 1.959963985;
  const double centre = (p + z * z / (2 * n)) / (1 + z * z / n);
  const double half = z * std::sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n);
  c.share = p;
  c.low = centre - half;
  c.high = centre + half;
  return c;
}

}  // namespace depthtrack
