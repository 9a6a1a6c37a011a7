#include "tracker/mutual_occlusion.hpp"

#include <cmath>
#include <depthtrack/error.hpp>
#include <limits>

namespace depthtrack {

MutualOcclusion::MutualOcclusion(const std::vector<Mesh>& meshes, const Camera& working, double near, double far)
    : working_(working) {
  for (const Mesh& mesh : meshes) {
    rasterizers_.emplace_back(mesh, working, near, far);
    centres_.push_back(mesh.centre().cast<double>());
    radii_.push_back(mesh.radius());
  }
}

DepthImage MutualOcclusion::frame_for(size_t object, const DepthImage& working_depth, const std::vector<Pose>& poses,
                                      size_t* masked) const {
  if (working_depth.width() != working_.width || working_depth.height() != working_.height)
    throw InputError("mutual occlusion: the frame is " + std::to_string(working_depth.width()) + "x" +
                     std::to_string(working_depth.height()) + ", not the working camera's " +
                     std::to_string(working_.width) + "x" + std::to_string(working_.height));
  const size_t pixels = static_cast<size_t>(working_.pixel_count());
  own_.assign(pixels, 0.0f);
  other_.assign(pixels, 0.0f);
  rasterizers_[object].render(poses[object], own_);
  // The nearest of the other objects' surfaces per pixel (0: none).
  std::vector<float> layer(pixels);
  for (size_t k = 0; k < rasterizers_.size(); ++k) {
    if (k == object) continue;
    std::fill(layer.begin(), layer.end(), 0.0f);
    rasterizers_[k].render(poses[k], layer);
    for (size_t i = 0; i < pixels; ++i)
      if (layer[i] > 0 && (other_[i] == 0 || layer[i] < other_[i])) other_[i] = layer[i];
  }
  const double nearest = (poses[object].rotation * centres_[object] + poses[object].translation).z() - radii_[object];
  DepthImage out = working_depth;
  size_t count = 0;
  for (int v = 0; v < working_.height; ++v)
    for (int u = 0; u < working_.width; ++u) {
      const size_t i = static_cast<size_t>(v) * working_.width + u;
      if (other_[i] == 0) continue;
      const double bound = own_[i] > 0 ? own_[i] - kMargin : nearest;
      if (other_[i] >= bound) continue;
      out.at(u, v) = std::numeric_limits<float>::quiet_NaN();
      ++count;
    }
  if (masked) *masked = count;
  return out;
}

}  // namespace depthtrack
