#pragma once
// A rigid transform camera_from_object: x_camera = rotation * x_object + translation (metres).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

namespace depthtrack {

struct Pose {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();

  Pose() = default;
  Pose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) : translation(t), rotation(q.normalized()) {}

  // From a row-major 4x4 matrix whose upper-left 3x3 block must be a rotation (checked).
  static Pose from_row_major(const std::array<double, 16>& m);
  Eigen::Matrix4d matrix() const;
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return rotation * x + translation; }
  Pose inverse() const;
  Pose operator*(const Pose& other) const;
};

// Rotation vector (axis * angle, radians) <-> rotation: the exponential and logarithm of SO(3).
Eigen::Quaterniond rotation_exp(const Eigen::Vector3d& rotation_vector);
Eigen::Vector3d rotation_log(const Eigen::Quaterniond& q);

// Pose error: translation distance (metres) and rotation angle (radians) between two poses.
double translation_error(const Pose& a, const Pose& b);
double rotation_error(const Pose& a, const Pose& b);

}  // namespace depthtrack
