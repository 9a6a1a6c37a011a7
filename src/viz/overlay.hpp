#pragma once
// Pictures of an estimate: its silhouette and depth edges drawn over the frame it was tracked in.
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <string>
#include <vector>

#include "reference/rasterizer.hpp"
#include "viz/rgb_image.hpp"

namespace depthtrack::viz {

// Depth as colour: near is light and warm, far dark blue, over the 0.1th..99.9th percentile of
// valid depths; pixels without a measurement are black.
RgbImage colour_mapped_depth(const DepthImage& depth);

// What the overlay marks, per pixel of the sensor image.
enum class OverlayMark : uint8_t {
  None,
  Inside,     // covered by the rendered estimate
  Outline,    // covered, next to an uncovered pixel: the silhouette's border
  DepthEdge,  // covered, the nearer side of a depth step to a covered neighbour (an inner edge)
};

class OverlayPainter {
 public:
  // Renders at the sensor's full resolution with the reference rasterizer.
  OverlayPainter(const Mesh& mesh, const Camera& sensor);

  // The marks of the mesh at pose, row-major, sensor width x height.
  std::vector<OverlayMark> marks(const Pose& camera_from_object) const;
  // background (the colour image, or colour_mapped_depth) with the estimate's marks and the text
  // lines in a box at the top left. background must have the sensor's size.
  RgbImage paint(const RgbImage& background, const Pose& camera_from_object,
                 const std::vector<std::string>& text) const;

 private:
  reference::Rasterizer rasterizer_;
  Camera sensor_;
};

}  // namespace depthtrack::viz
