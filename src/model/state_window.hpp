#pragma once
// The occlusion state window (TrackerConfig::occlusion_window): the rectangle of the working image in
// which every particle keeps its per-pixel occlusion state, rows of width x height values. The
// reference and the device filters place it with these same functions, from the same poses, so both
// keep the same pixels. Its pixels outside the last frame's window start fresh.
#include <cstddef>
#include <depthtrack/camera.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>

namespace depthtrack::model {

struct StateWindow {
  int u0 = 0, v0 = 0;         // top-left pixel, inside the image
  int width = 0, height = 0;  // at most the image's

  size_t pixels() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  bool contains(int u, int v) const { return u >= u0 && u < u0 + width && v >= v0 && v < v0 + height; }
  // Index of image pixel (u, v) in a particle's row; only for pixels the window contains.
  size_t index(int u, int v) const {
    return static_cast<size_t>(v - v0) * static_cast<size_t>(width) + static_cast<size_t>(u - u0);
  }
  bool operator==(const StateWindow&) const = default;
};

// The configured size (0 or more than the image: the image's), at the image's top-left corner.
StateWindow state_window_size(const TrackerConfig& config, const Camera& camera);

// `window` moved so that its centre is the pixel nearest to the projection of the mesh centre
// (object frame) in `pose`, clamped inside the image; unmoved when that point is not in front of the
// camera or not finite.
StateWindow state_window_at(StateWindow window, const Pose& pose, const Eigen::Vector3d& centre, const Camera& camera);

}  // namespace depthtrack::model
