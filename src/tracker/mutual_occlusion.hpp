#pragma once
// Objects tracked together hide each other: before one object's update, the others' latest estimates
// are drawn (reference rasterizer, working resolution) and the pixels where another object's surface is
// nearer than this object can be are made missing in its frame, so its likelihood neither rewards nor
// punishes them. "Can be": its own estimate's depth there, less a margin, where that covers the pixel;
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
  // working: the trackers' working camera; decimation: sensor pixels per working pixel (each working pixel
  // is the sensor's pixel (k u, k v), as DepthImage::decimated keeps it).
  MutualOcclusion(const std::vector<Mesh>& meshes, const Camera& working, int decimation, double near, double far);

  // The sensor frame for object `object`, with the pixels the other objects hide (at poses) missing;
  // masked (if not null) receives how many working pixels were.
  DepthImage frame_for(size_t object, const DepthImage& sensor_depth, const std::vector<Pose>& poses,
                       size_t* masked = nullptr) const;

  // An estimate this far behind another object's surface still counts as seen (estimates are off by mm).
  static constexpr double kMargin = 0.01;  // metres

 private:
  std::vector<reference::Rasterizer> rasterizers_;
  std::vector<Eigen::Vector3d> centres_;
  std::vector<double> radii_;
  Camera working_;
  int decimation_;
  mutable std::vector<float> own_, other_;  // scratch renderings
};

}  // namespace depthtrack
