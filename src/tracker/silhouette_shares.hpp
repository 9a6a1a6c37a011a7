#pragma once
// How the depth explains a pose's rendered silhouette: shares that mean the same for any object and
// resolution, from which the tracker's confidence is built.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>

#include "reference/rasterizer.hpp"

namespace depthtrack {

struct SilhouetteShares {
  int pixels = 0;           // rendered silhouette, working pixels
  double visible = 0;       // of those with valid depth: |y - y_hat| <= k sigma(y)
  double occluded = 0;      // y in front of the surface: something hides it
  double contradicted = 0;  // y behind the surface: the camera sees through where the object would be
  double missing = 0;       // of all silhouette pixels: no valid depth
  // Of the outline's outer neighbours (uncovered pixels next to a covered one) not against a
  // nearer surface: the share where the camera sees past the object's edge (depth behind it, or
  // none: sensors drop pixels at depth edges). An object stands out from what is behind it; a pose
  // pressed flat into a wall has a surface that fits but no outline. An edge against something
  // nearer (an occluder, or the object itself when the pose is a pixel off) says neither.
  double separated = 0;
  double outline_nearer = 0;  // of all the outline's outer neighbours: seen in front of the edge
  // visible share of the pixels with valid depth; 0 for an empty or unmeasured silhouette.
  double confidence() const { return visible; }
};

SilhouetteShares silhouette_shares(const reference::Rasterizer& rasterizer, const ObservationModel& model,
                                   double pixel_sigmas, const Pose& pose, const DepthImage& depth,
                                   std::span<float> scratch);

}  // namespace depthtrack
