#pragma once
// The occlusion state window (TrackerConfig::occlusion_window): the rectangle of the working image in
// which every particle keeps its per-pixel occlusion state, rows of width x height values. The
// reference and the device filters size and place it with these same functions, from the same poses,
// so both keep the same pixels. Its pixels outside the last frame's window start fresh.
#include <cstddef>
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <optional>
#include <string>
#include <vector>

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

// What the automatic window is sized from, in the object frame: points whose projections reach as far as
// the mesh's (the vertices of its convex hull: a few hundred of a scanned mesh's thousands, projected each
// frame on the host; the 8 corners of its bounding box where the mesh spans no volume, which reach
// farther) and the point the window is centred on (the mesh centre).
struct ObjectExtent {
  std::vector<Eigen::Vector3d> bounding_points;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
ObjectExtent object_extent(const Mesh& mesh);

// Margins of the automatic window beyond the projected box, each side: a share of the box's half-size
// (the particles' spread and a frame's motion, which scale with the object's size in pixels) and a few
// pixels (rounding at coarse resolutions).
constexpr double kAutomaticWindowShare = 0.2;
constexpr double kAutomaticWindowPixels = 2.0;

// The configured size at the image's top-left corner: a fixed one (0 or more than the image in a
// dimension: the image's), the whole image, or 0 x 0 for the automatic window until a start sizes it.
StateWindow state_window_size(const TrackerConfig& config, const Camera& camera);

// The automatic window's size for the object at `pose`: odd sides centred on the pixel nearest the
// projected mesh centre (where state_window_at puts the middle), reaching every pixel centre within the
// projection of the bounding points plus the margins; clamped to the image, and the whole image where a
// bounding point lies behind the camera plane. Nothing where the mesh centre is not in front of the camera or
// not finite (the pose says nothing about the object's size in the image).
std::optional<StateWindow> automatic_window_size(const ObjectExtent& object, const Pose& pose, const Camera& camera);

// The window at a start from `pose`: the configured size (automatic: sized at the pose, the whole image
// where the pose says nothing) placed at it.
StateWindow start_state_window(const TrackerConfig& config, const ObjectExtent& object, const Pose& pose,
                               const Camera& camera);

// The window for the frame after the one that estimated `estimate`: an automatic window grown (never
// shrunk) to hold the estimate's size, unless that would pass max_pixels (0: no bound; the filter's
// memory), then placed at the estimate.
StateWindow next_state_window(StateWindow window, const TrackerConfig& config, const ObjectExtent& object,
                              const Pose& estimate, const Camera& camera, size_t max_pixels);

// "N particles at WxH", and where an automatic window has been sized " with a WxH occlusion state window
// (sized for the object at its start)": what the reference's and the device's memory errors say did not fit.
std::string particles_and_window(const TrackerConfig& config, const Camera& camera, const StateWindow& window);

// `window` moved so that its centre is the pixel nearest to the projection of the mesh centre
// (object frame) in `pose`, clamped inside the image; unmoved when that point is not in front of the
// camera or not finite.
StateWindow state_window_at(StateWindow window, const Pose& pose, const Eigen::Vector3d& centre, const Camera& camera);

}  // namespace depthtrack::model
