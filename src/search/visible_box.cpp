#include "search/visible_box.hpp"

#include <algorithm>
#include <cmath>

#include "reference/observation_model.hpp"

namespace depthtrack::search {

ImageBox hint_box(const InitHint& hint, int decimation) {
  if (hint.kind != InitHint::Kind::Box) return {};
  // Working pixel u is sensor pixel decimation * u (Camera::decimated): coordinates scale by 1/decimation.
  const double d = std::max(decimation, 1);
  return {(hint.u0 - 0.5) / d, (hint.v0 - 0.5) / d, (hint.u1 + 0.5) / d, (hint.v1 + 0.5) / d};
}

ImageBox visible_box(std::span<const Eigen::Vector3d> points, const Pose& pose, const Camera& camera,
                     const DepthImage& depth, const ObservationModel& model, double pixel_sigmas) {
  ImageBox box{static_cast<double>(camera.width), static_cast<double>(camera.height), -1, -1};
  bool any = false;
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  for (const Eigen::Vector3d& x : points) {
    const Eigen::Vector3d p = r * x + pose.translation;
    if (!(p.z() > 0)) continue;
    const Eigen::Vector2d uv = camera.project(p);
    const long u = std::lround(uv.x()), v = std::lround(uv.y());
    if (u < 0 || v < 0 || u >= depth.width() || v >= depth.height()) continue;
    const float y = depth.data()[static_cast<size_t>(v) * static_cast<size_t>(depth.width()) + static_cast<size_t>(u)];
    if (DepthImage::is_valid(y) && reference::band_side(model, pixel_sigmas, y, p.z()) == reference::BandSide::Nearer)
      continue;  // something in front hides it
    any = true;
    box.u0 = std::min(box.u0, uv.x());
    box.v0 = std::min(box.v0, uv.y());
    box.u1 = std::max(box.u1, uv.x());
    box.v1 = std::max(box.v1, uv.y());
  }
  return any ? box : ImageBox{};
}

double box_iou(const ImageBox& a, const ImageBox& b) {
  if (a.empty() || b.empty()) return 0.0;
  const ImageBox both{std::max(a.u0, b.u0), std::max(a.v0, b.v0), std::min(a.u1, b.u1), std::min(a.v1, b.v1)};
  const double common = both.area();
  const double all = a.area() + b.area() - common;
  return all > 0 ? common / all : 0.0;
}

}  // namespace depthtrack::search
