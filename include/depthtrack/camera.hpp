#pragma once
/// @file
/// Pinhole intrinsics of a depth camera, OpenCV convention: x right, y down, z forward, and the
/// centre of integer pixel (u, v) at image coordinate (u, v), so cx is about (width - 1) / 2.
#include <Eigen/Core>

namespace depthtrack {

/// Pinhole intrinsics (see the file's notes): the image size in pixels, focal lengths and centre in pixels.
struct Camera {
  int width = 0;                          ///< pixels
  int height = 0;                         ///< pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;  ///< focal lengths and principal point, pixels

  /// Checks the values and throws InputError naming the first impossible one.
  static Camera make(int width, int height, double fx, double fy, double cx, double cy);
  /// InputError naming the first impossible value: a non-positive size or focal length, a centre outside
  /// the image, a value that is not finite.
  void validate() const;
  /// From a 3x3 intrinsic matrix K = [fx 0 cx; 0 fy cy; 0 0 1] (OpenCV's cameraMatrix, ROS
  /// CameraInfo.k): InputError for skew, any other non-zero off-diagonal entry, a last row that is not
  /// 0 0 1, a non-finite entry, or what make() rejects (non-positive focal length, impossible centre).
  static Camera from_matrix(int width, int height, const Eigen::Matrix3d& K);
  Eigen::Matrix3d matrix() const;  ///< K

  /// The camera of an image made by keeping every factor-th pixel, starting with pixel (0, 0):
  /// pixel (u', v') of the result is pixel (factor u', factor v') of the original, so
  /// fx' = fx / factor and cx' = cx / factor. Width and height must be divisible by factor.
  Camera decimated(int factor) const;
  /// The decimation factor that turns this camera into one of the given size (both axes alike).
  int decimation_factor_for(int target_width, int target_height) const;

  /// Image coordinates of a camera-frame point (z > 0).
  Eigen::Vector2d project(const Eigen::Vector3d& p) const { return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy}; }
  /// The camera-frame point at depth z seen through image coordinates (u, v).
  Eigen::Vector3d back_project(double u, double v, double z) const { return {(u - cx) / fx * z, (v - cy) / fy * z, z}; }
  /// width * height.
  int pixel_count() const { return width * height; }
};

}  // namespace depthtrack
