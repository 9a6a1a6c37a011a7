#include "model/state_window.hpp"

#include <algorithm>
#include <cmath>

namespace depthtrack::model {

StateWindow state_window_size(const TrackerConfig& config, const Camera& camera) {
  const OcclusionWindow& w = config.occlusion_window;
  StateWindow window;
  window.width = w.width <= 0 ? camera.width : std::min(w.width, camera.width);
  window.height = w.height <= 0 ? camera.height : std::min(w.height, camera.height);
  return window;
}

StateWindow state_window_at(StateWindow window, const Pose& pose, const Eigen::Vector3d& centre, const Camera& camera) {
  const Eigen::Vector3d c = pose.rotation * centre + pose.translation;
  if (!(c.z() > 0) || !c.allFinite()) return window;
  const Eigen::Vector2d p = camera.project(c);
  // Bounded before the conversion: a point far off the image still clamps to its edge.
  auto origin = [](double at, int size, int image) {
    const double nearest = std::floor(std::clamp(at, -1e6, 1e6) + 0.5);
    return std::clamp(static_cast<int>(nearest) - size / 2, 0, image - size);
  };
  window.u0 = origin(p.x(), window.width, camera.width);
  window.v0 = origin(p.y(), window.height, camera.height);
  return window;
}

}  // namespace depthtrack::model
