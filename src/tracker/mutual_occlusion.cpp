#include "tracker/mutual_occlusion.hpp"

#include <cmath>
#include <depthtrack/error.hpp>
#include <limits>

namespace depthtrack {

MutualOcclusion::MutualOcclusion(const std::vector<Mesh>& meshes, const Camera& working) : working_(working) {
  for (const Mesh& mesh : meshes) {
    centres_.push_back(mesh.centre().cast<double>());
    radii_.push_back(mesh.radius());
  }
}

DepthImage MutualOcclusion::frame_for(size_t object, const DepthImage& working_depth, const std::vector<Pose>& poses,
                                      const std::vector<std::vector<float>>& layers, size_t* masked) const {
  if (working_depth.width() != working_.width || working_depth.height() != working_.height)
    throw InputError("mutual occlusion: the frame is " + std::to_string(working_depth.width()) + "x" +
                     std::to_string(working_depth.height()) + ", not the working camera's " +
                     std::to_string(working_.width) + "x" + std::to_string(working_.height));
  const size_t pixels = static_cast<size_t>(working_.pixel_count());
  if (poses.size() != centres_.size() || layers.size() != centres_.size())
    throw InputError("mutual occlusion: " + std::to_string(poses.size()) + " poses and " +
                     std::to_string(layers.size()) + " layers for " + std::to_string(centres_.size()) + " objects");
  for (const auto& layer : layers)
    if (layer.size() != pixels)
      throw InputError("mutual occlusion: a layer of " + std::to_string(layer.size()) + " pixels, not the working " +
                       "camera's " + std::to_string(pixels));
  const std::vector<float>& own = layers[object];
  // The nearest of the other objects' surfaces per pixel (0: none).
  std::vector<float> other(pixels, 0.0f);
  for (size_t k = 0; k < layers.size(); ++k) {
    if (k == object) continue;
    for (size_t i = 0; i < pixels; ++i)
      if (layers[k][i] > 0 && (other[i] == 0 || layers[k][i] < other[i])) other[i] = layers[k][i];
  }
  const double nearest = (poses[object].rotation * centres_[object] + poses[object].translation).z() - radii_[object];
  DepthImage out = working_depth;
  size_t count = 0;
  for (int v = 0; v < working_.height; ++v)
    for (int u = 0; u < working_.width; ++u) {
      const size_t i = static_cast<size_t>(v) * working_.width + u;
      if (other[i] == 0) continue;
      const double bound = own[i] > 0 ? own[i] - kMargin : nearest;
      if (other[i] >= bound) continue;
      out.at(u, v) = std::numeric_limits<float>::quiet_NaN();
      ++count;
    }
  if (masked) *masked = count;
  return out;
}

}  // namespace depthtrack
