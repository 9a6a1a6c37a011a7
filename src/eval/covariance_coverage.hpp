#pragma once
// Whether the reported covariance holds: per frame, the estimate's error against the ground truth in the
// covariance's own parametrization, its Mahalanobis distance, and whether it falls inside the 95 % region;
// per run, the share of frames that do.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <depthtrack/estimate.hpp>
#include <depthtrack/pose.hpp>
#include <optional>
#include <vector>

namespace depthtrack {

// The error of estimate against truth as Estimate::covariance parametrizes it: a camera-frame twist about
// the mesh's centre (object frame), rows 0-2 the centre's displacement (m), 3-5 the rotation vector of
// R_estimate R_truth^T (rad).
Eigen::Matrix<double, 6, 1> pose_error_twist(const Pose& estimate, const Pose& truth, const Eigen::Vector3d& centre);

// The 0.95 quantile of the chi-squared distribution with dof degrees of freedom (1 to 6).
double chi2_95(int dof);

struct CovarianceCheck {
  double d2 = 0;        // e^T Sigma^-1 e over the determined directions
  int dof = 0;          // how many: of the axes with a finite variance, the principal directions of their
                        // block with a variance under model::kDeterminedBelow
  bool inside = false;  // d2 <= chi2_95(dof)
  // Each coordinate axis' own share (x, y, z, rx, ry, rz): error_i^2 / Sigma_ii, chi-squared with one degree
  // of freedom where the covariance holds (median 0.45, 95 % under 3.84): which axes a region too wide or
  // too narrow is so on. NaN where the axis' variance is +infinity or at least model::kDeterminedBelow.
  std::array<double, 6> axis_d2{NAN, NAN, NAN, NAN, NAN, NAN};
};

// The check of error against covariance; axes with +infinity on the diagonal (undetermined) are left out,
// and so are the finite block's principal directions with a variance of model::kDeterminedBelow or more.
// nullopt when the covariance has a NaN (refinement off, too few pixels), no determined direction (a lost
// or barely supported estimate), or its finite block is not positive definite.
std::optional<CovarianceCheck> check_covariance(const Eigen::Matrix<double, 6, 1>& error,
                                                const Eigen::Matrix<double, 6, 6>& covariance);

// The share of checked frames inside their 95 % region, with its Wilson score interval at 95 %; and the
// frames with ground truth that had no region to check (no determined direction, or NaN), counted apart.
struct Coverage {
  size_t checked = 0, inside = 0, no_region = 0;
  double share = NAN, low = NAN, high = NAN;
};
Coverage coverage(const std::vector<CovarianceCheck>& checks, size_t no_region = 0);

}  // namespace depthtrack
