#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/pose.hpp>

namespace depthtrack {

Pose Pose::from_row_major(const std::array<double, 16>& m) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m[static_cast<size_t>(i * 4 + j)];
  for (double v : m)
    if (!std::isfinite(v)) throw InputError("pose matrix has a non-finite entry");
  const double orthogonality = (r.transpose() * r - Eigen::Matrix3d::Identity()).norm();
  if (orthogonality > 1e-3 || r.determinant() < 0)
    throw InputError("pose matrix's 3x3 block is not a rotation (|R^T R - I| = " + std::to_string(orthogonality) + ")");
  return Pose({m[3], m[7], m[11]}, Eigen::Quaterniond(r));
}

Eigen::Matrix4d Pose::matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<3, 3>(0, 0) = rotation.toRotationMatrix();
  m.block<3, 1>(0, 3) = translation;
  return m;
}

Pose Pose::inverse() const {
  const Eigen::Quaterniond inv = rotation.conjugate();
  return Pose(-(inv * translation), inv);
}

Pose Pose::operator*(const Pose& other) const {
  return Pose(rotation * other.translation + translation, rotation * other.rotation);
}

Eigen::Quaterniond rotation_exp(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

Eigen::Vector3d rotation_log(const Eigen::Quaterniond& q_in) {
  Eigen::Quaterniond q = q_in.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // the shorter way round
  const double s = q.vec().norm();
  if (s < 1e-12) return 2.0 * q.vec();
  const double angle = 2.0 * std::atan2(s, q.w());
  return q.vec() * (angle / s);
}

double translation_error(const Pose& a, const Pose& b) {
  return (a.translation - b.translation).norm();
}

double rotation_error(const Pose& a, const Pose& b) {
  return rotation_log(a.rotation.conjugate() * b.rotation).norm();
}

}  // namespace depthtrack
