#pragma once
/// @file
/// Where global initialization looks for the object: anywhere, inside a 2D box of the sensor image
/// (what a detector gives), or near a 3D point.
#include <Eigen/Core>
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>

namespace depthtrack {

/// Where Tracker::initialize_global looks (see the file's notes); make one with anywhere(), box() or near_point().
struct InitHint {
  /// Which region the hint gives.
  enum class Kind {
    None,   ///< the whole image
    Box,    ///< a box of sensor pixels
    Point,  ///< near a camera-frame point
  };
  Kind kind = Kind::None;                           ///< which of the fields below apply
  int u0 = 0, v0 = 0, u1 = 0, v1 = 0;               ///< Box: inclusive sensor pixels, u0 <= u1, v0 <= v1
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< Point: camera frame, metres, on or near the object

  /// The whole image.
  static InitHint anywhere() { return {}; }
  /// The box of sensor pixels u0..u1, v0..v1 (inclusive); Tracker::initialize_global throws InputError for an
  /// empty box or one outside the image. It is taken as a detector's box, bounding the object's visible
  /// pixels: poses whose visible pixels' box agrees with it least rank below the others.
  static InitHint box(int u0, int v0, int u1, int v1) {
    InitHint h;
    h.kind = Kind::Box;
    h.u0 = u0;
    h.v0 = v0;
    h.u1 = u1;
    h.v1 = v1;
    return h;
  }
  /// Near p (camera frame, metres).
  static InitHint near_point(const Eigen::Vector3d& p) {
    InitHint h;
    h.kind = Kind::Point;
    h.point = p;
    return h;
  }
};

/// The box of sensor pixels around the mesh's vertices projected at `pose`, clamped to the image: what a
/// detector would give for an object seen there (tests and benchmarks start global search from it).
InitHint projected_box(const Mesh& mesh, const Camera& camera, const Pose& pose);

}  // namespace depthtrack
