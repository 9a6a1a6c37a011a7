#pragma once
/// @file
/// A rigid transform camera_from_object: x_camera = rotation * x_object + translation (metres).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

namespace depthtrack {

/// A rigid transform camera_from_object: x_camera = rotation * x_object + translation.
struct Pose {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();         ///< metres
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  ///< unit quaternion

  /// The identity.
  Pose() = default;
  /// From a translation (metres) and a rotation, normalized here.
  Pose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) : translation(t), rotation(q.normalized()) {}

  /// From a row-major 4x4 matrix whose upper-left 3x3 block must be a rotation (checked).
  static Pose from_row_major(const std::array<double, 16>& m);
  /// The homogeneous 4x4 matrix [R t; 0 1].
  Eigen::Matrix4d matrix() const;
  /// rotation * x + translation: an object-frame point in the camera frame.
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return rotation * x + translation; }
  /// object_from_camera.
  Pose inverse() const;
  /// The composition: (*this * other).apply(x) == apply(other.apply(x)).
  Pose operator*(const Pose& other) const;
};

/// Rotation vector (axis * angle, radians) <-> rotation: the exponential and logarithm of SO(3).
Eigen::Quaterniond rotation_exp(const Eigen::Vector3d& rotation_vector);
/// The rotation vector (radians, angle in [0, pi]) of q: rotation_exp's inverse.
Eigen::Vector3d rotation_log(const Eigen::Quaterniond& q);

/// Pose error: translation distance (metres) and rotation angle (radians) between two poses.
double translation_error(const Pose& a, const Pose& b);
/// The angle (radians, in [0, pi]) of the rotation between a's and b's.
double rotation_error(const Pose& a, const Pose& b);

}  // namespace depthtrack
