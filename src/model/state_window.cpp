#include "model/state_window.hpp"

#include <algorithm>
#include <cmath>

#include "core/convex_hull.hpp"

namespace depthtrack::model {

ObjectExtent object_extent(const Mesh& mesh) {
  ObjectExtent extent;
  extent.centre = mesh.centre().cast<double>();
  if (const auto hull = convex_hull_vertices(mesh.vertices)) {
    for (const int i : *hull) extent.bounding_points.push_back(mesh.vertices[static_cast<size_t>(i)].cast<double>());
    return extent;
  }
  Eigen::Vector3d low = extent.centre, high = extent.centre;
  for (const auto& v : mesh.vertices) {
    low = low.cwiseMin(v.cast<double>());
    high = high.cwiseMax(v.cast<double>());
  }
  for (int i = 0; i < 8; ++i)
    extent.bounding_points.emplace_back((i & 1) ? high.x() : low.x(), (i & 2) ? high.y() : low.y(),
                                        (i & 4) ? high.z() : low.z());
  return extent;
}

StateWindow state_window_size(const TrackerConfig& config, const Camera& camera) {
  const OcclusionWindow& w = config.occlusion_window;
  StateWindow window;
  if (w.is_automatic()) return window;  // sized at the start
  window.width = w.width <= 0 ? camera.width : std::min(w.width, camera.width);
  window.height = w.height <= 0 ? camera.height : std::min(w.height, camera.height);
  return window;
}

namespace {
StateWindow whole_image(const Camera& camera) {
  StateWindow window;
  window.width = camera.width;
  window.height = camera.height;
  return window;
}

// An odd side around the centre's pixel that reaches `half` pixels from the projected centre (which is
// up to half a pixel from that pixel's centre) and the margins beyond.
int automatic_side(double half, int image) {
  const double reach = half * (1 + kAutomaticWindowShare) + kAutomaticWindowPixels + 0.5;
  if (!(reach < image)) return image;
  return std::min(image, 2 * static_cast<int>(std::ceil(reach)) + 1);
}
}  // namespace

std::optional<StateWindow> automatic_window_size(const ObjectExtent& object, const Pose& pose, const Camera& camera) {
  const Eigen::Vector3d c = pose.rotation * object.centre + pose.translation;
  if (!(c.z() > 0) || !c.allFinite()) return std::nullopt;
  const Eigen::Vector2d middle = camera.project(c);
  double half_u = 0, half_v = 0;
  for (const Eigen::Vector3d& point : object.bounding_points) {
    const Eigen::Vector3d p = pose.rotation * point + pose.translation;
    if (!(p.z() > 0) || !p.allFinite()) return whole_image(camera);  // its projection is unbounded
    const Eigen::Vector2d q = camera.project(p);
    half_u = std::max(half_u, std::abs(q.x() - middle.x()));
    half_v = std::max(half_v, std::abs(q.y() - middle.y()));
  }
  StateWindow window;
  window.width = automatic_side(half_u, camera.width);
  window.height = automatic_side(half_v, camera.height);
  return window;
}

StateWindow start_state_window(const TrackerConfig& config, const ObjectExtent& object, const Pose& pose,
                               const Camera& camera) {
  StateWindow window = state_window_size(config, camera);
  if (config.occlusion_window.is_automatic())
    window = automatic_window_size(object, pose, camera).value_or(whole_image(camera));
  return state_window_at(window, pose, object.centre, camera);
}

StateWindow next_state_window(StateWindow window, const TrackerConfig& config, const ObjectExtent& object,
                              const Pose& estimate, const Camera& camera, size_t max_pixels) {
  if (config.occlusion_window.is_automatic())
    if (const auto wanted = automatic_window_size(object, estimate, camera)) {
      StateWindow grown = window;
      grown.width = std::max(window.width, wanted->width);
      grown.height = std::max(window.height, wanted->height);
      if (max_pixels == 0 || grown.pixels() <= max_pixels) window = grown;
    }
  return state_window_at(window, estimate, object.centre, camera);
}

std::string particles_and_window(const TrackerConfig& config, const Camera& camera, const StateWindow& window) {
  std::string text = std::to_string(config.particles) + " particles at " + std::to_string(camera.width) + "x" +
                     std::to_string(camera.height);
  if (config.occlusion_window.is_automatic() && window.pixels() > 0)
    text += " with a " + std::to_string(window.width) + "x" + std::to_string(window.height) +
            " occlusion state window (sized for the object at its start)";
  return text;
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
