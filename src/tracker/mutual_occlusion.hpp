#pragma once
// Objects tracked together hide each other: before a frame, the pixels where another object's surface
// (its previous estimate drawn at the working camera: a layer) is nearer than this object can be are made
// missing in its working frame, so its likelihood neither rewards nor punishes them. "Can be": its own
// estimate's depth there, less a margin, where that covers the pixel; elsewhere the nearest its mesh can
// come (its centre's depth less its radius).
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <vector>

namespace depthtrack {

class MutualOcclusion {
 public:
  // working: the trackers' working camera.
  MutualOcclusion(const std::vector<Mesh>& meshes, const Camera& working);

  // The working frame for object `object`, with the pixels the other objects hide missing: layers[k] is
  // object k's depth at poses[k] (working camera, row-major, 0 where it covers nothing; a tracker's
  // silhouette); masked (if not null) receives how many were.
  DepthImage frame_for(size_t object, const DepthImage& working_depth, const std::vector<Pose>& poses,
                       const std::vector<std::vector<float>>& layers, size_t* masked = nullptr) const;

  // An estimate this far behind another object's surface still counts as seen (estimates are off by mm).
  static constexpr double kMargin = 0.01;  // metres

 private:
  std::vector<Eigen::Vector3d> centres_;
  std::vector<double> radii_;
  Camera working_;
};

}  // namespace depthtrack
