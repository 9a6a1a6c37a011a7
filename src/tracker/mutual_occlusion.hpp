#pragma once
// Objects tracked together hide each other: before a frame, the others' previous estimates are drawn
// (reference rasterizer, working camera: 80x60 costs little on the host) and the pixels where another
// object's surface is nearer than this object can be are made missing in its working frame, so its likelihood neither
// rewards nor punishes them. "Can be": its own estimate's depth there, less a margin, where that covers the pixel;
// elsewhere the nearest its mesh can come (its centre's depth less its radius).
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <vector>

#include "reference/rasterizer.hpp"

namespace depthtrack {

class MutualOcclusion {
 public:
  // working: the trackers' working camera.
  MutualOcclusion(const std::vector<Mesh>& meshes, const Camera& working, double near, double far);

  // Every object's depth at its pose (0 where it covers nothing), each drawn once, on a thread per
  // object: what the objects' working frames are masked from.
  std::vector<std::vector<float>> draw(const std::vector<Pose>& poses) const;

  // The working frame for object `object`, with the pixels the other objects hide (at poses, drawn as
  // `layers` by draw()) missing; masked (if not null) receives how many were.
  DepthImage frame_for(size_t object, const DepthImage& working_depth, const std::vector<Pose>& poses,
                       const std::vector<std::vector<float>>& layers, size_t* masked = nullptr) const;
  // The same, drawing the layers itself.
  DepthImage frame_for(size_t object, const DepthImage& working_depth, const std::vector<Pose>& poses,
                       size_t* masked = nullptr) const;

  // An estimate this far behind another object's surface still counts as seen (estimates are off by mm).
  static constexpr double kMargin = 0.01;  // metres

 private:
  std::vector<reference::Rasterizer> rasterizers_;
  std::vector<Eigen::Vector3d> centres_;
  std::vector<double> radii_;
  Camera working_;
};

}  // namespace depthtrack
