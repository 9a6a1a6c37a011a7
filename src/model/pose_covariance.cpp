#include "model/pose_covariance.hpp"

#include <array>
#include <cmath>
#include <limits>

namespace depthtrack::model {

namespace {
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Which axes the pixels determine: the pivoted factorization of the header, on the unit-diagonal c
// with weight[i] = H_ii (in metres) turning its Schur complements into information.
std::array<bool, 6> determined_axes(Matrix6d c, const std::array<double, 6>& weight, std::array<bool, 6> left) {
  std::array<bool, 6> taken{};
  for (;;) {
    int pivot = -1;
    for (int i = 0; i < 6; ++i) {
      if (!left[i]) continue;
      if (!(c(i, i) >= 1.0 / kMaxVarianceInflation)) {
        left[i] = false;  // explained by the axes taken
        continue;
      }
      if (pivot < 0 || c(i, i) * weight[i] > c(pivot, pivot) * weight[pivot]) pivot = i;
    }
    if (pivot < 0) return taken;
    taken[pivot] = true;
    left[pivot] = false;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        if (left[i] && left[j]) c(i, j) -= c(i, pivot) * c(j, pivot) / c(pivot, pivot);
  }
}

// The inverse of c's block of the taken axes (0 elsewhere), by its Cholesky factor; false if a pivot
// is not positive.
bool invert_block(const Matrix6d& c, const std::array<bool, 6>& taken, Matrix6d& inverse) {
  Matrix6d l = Matrix6d::Zero();
  for (int j = 0; j < 6; ++j) {
    if (!taken[j]) continue;
    double d = c(j, j);
    for (int m = 0; m < j; ++m) d -= l(j, m) * l(j, m);
    if (!(d > 0)) return false;
    l(j, j) = std::sqrt(d);
    for (int i = j + 1; i < 6; ++i) {
      if (!taken[i]) continue;
      double e = c(i, j);
      for (int m = 0; m < j; ++m) e -= l(i, m) * l(j, m);
      l(i, j) = e / l(j, j);
    }
  }
  inverse.setZero();
  for (int k = 0; k < 6; ++k) {  // column k: L y = e_k, then L^T x = y
    if (!taken[k]) continue;
    double y[6] = {0, 0, 0, 0, 0, 0}, x[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < 6; ++i) {
      if (!taken[i]) continue;
      double e = i == k ? 1.0 : 0.0;
      for (int m = 0; m < i; ++m) e -= l(i, m) * y[m];
      y[i] = e / l(i, i);
    }
    for (int i = 5; i >= 0; --i) {
      if (!taken[i]) continue;
      double e = y[i];
      for (int m = i + 1; m < 6; ++m) e -= l(m, i) * x[m];
      x[i] = e / l(i, i);
    }
    for (int i = 0; i < 6; ++i) inverse(i, k) = x[i];
  }
  return true;
}
}  // namespace

Matrix6d pose_covariance(const Matrix6d& h, int pixels, double radius) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (pixels < 6) return Matrix6d::Constant(nan);
  std::array<bool, 6> left{};
  std::array<double, 6> scale{}, weight{};
  for (int i = 0; i < 6; ++i) {
    left[i] = h(i, i) > 0 && std::isfinite(h(i, i));
    scale[i] = left[i] ? 1.0 / std::sqrt(h(i, i)) : 0.0;
    weight[i] = i < 3 || !(radius > 0) ? h(i, i) : h(i, i) / (radius * radius);
  }
  Matrix6d c;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) c(i, j) = scale[i] * h(i, j) * scale[j];
  const std::array<bool, 6> taken = determined_axes(c, weight, left);
  Matrix6d inverse;
  if (!invert_block(c, taken, inverse)) return Matrix6d::Constant(nan);
  Matrix6d covariance;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      covariance(i, j) = taken[i] && taken[j] ? scale[i] * inverse(i, j) * scale[j]
                         : i == j             ? std::numeric_limits<double>::infinity()
                                              : 0.0;
  return covariance;
}

}  // namespace depthtrack::model
