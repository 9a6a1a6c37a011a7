#pragma once
// The box of a pose's visible silhouette, and how well it agrees with a detector's box. A detector's
// box bounds the object's visible pixels: a right pose's surface not hidden by what the frame sees in
// front of it spans about that box, while a pose sunk behind other surfaces (its pixels explained as
// occluded) or slid aside does not.
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/init_hint.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>

namespace depthtrack::search {

// A box in continuous image coordinates (pixel centres at whole numbers); empty when u1 < u0.
struct ImageBox {
  double u0 = 0, v0 = 0, u1 = -1, v1 = -1;
  bool empty() const { return u1 < u0 || v1 < v0; }
  double area() const { return empty() ? 0.0 : (u1 - u0) * (v1 - v0); }
};

// The hint's box (inclusive sensor pixels, their edges included) in the coordinates of `camera`, a
// decimation of the sensor by `decimation`. Empty unless the hint is a box.
ImageBox hint_box(const InitHint& hint, int decimation);

// The box of the surface points (object frame) that `depth` (camera's resolution) does not see
// hidden at `pose`: a point is hidden where a valid depth lies nearer than it by more than
// pixel_sigmas sigma(y) of `model` (reference::band_side: Nearer, as silhouette_shares counts an
// occluded pixel); a point with no depth there, or one within or behind the band, is visible. Points
// outside the image or behind the camera are left out. A point behind the surface in front at its own
// pixel is hidden by it whenever that surface is, so the box is that of the pose's visible pixels
// (up to the points' spacing).
ImageBox visible_box(std::span<const Eigen::Vector3d> points, const Pose& pose, const Camera& camera,
                     const DepthImage& depth, const ObservationModel& model, double pixel_sigmas);

// Intersection over union; 0 when either is empty.
double box_iou(const ImageBox& a, const ImageBox& b);

}  // namespace depthtrack::search
