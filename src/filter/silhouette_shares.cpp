#include "filter/silhouette_shares.hpp"

#include "reference/observation_model.hpp"

namespace depthtrack {

SilhouetteShares silhouette_shares(const reference::Rasterizer& rasterizer, const ObservationModel& model,
                                   double pixel_sigmas, const Pose& pose, const DepthImage& depth,
                                   std::span<float> scratch) {
  const reference::PixelBox box = rasterizer.render(pose, scratch);
  const int width = rasterizer.camera().width;
  int visible = 0, occluded = 0, contradicted = 0, missing = 0;
  for (int v = box.v0; v < box.v1; ++v)
    for (int u = box.u0; u < box.u1; ++u) {
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u);
      const double y_hat = scratch[k];
      if (y_hat <= 0) continue;
      const float y = depth.data()[k];
      if (!DepthImage::is_valid(y)) {
        ++missing;
        continue;
      }
      const double band = pixel_sigmas * reference::depth_sigma(model, y);
      if (y < y_hat - band)
        ++occluded;
      else if (y > y_hat + band)
        ++contradicted;
      else
        ++visible;
    }
  SilhouetteShares s;
  s.pixels = visible + occluded + contradicted + missing;
  const int measured = visible + occluded + contradicted;
  if (s.pixels > 0) s.missing = static_cast<double>(missing) / s.pixels;
  if (measured > 0) {
    s.visible = static_cast<double>(visible) / measured;
    s.occluded = static_cast<double>(occluded) / measured;
    s.contradicted = static_cast<double>(contradicted) / measured;
  }
  return s;
}

}  // namespace depthtrack
