// The atlas drawn tile by tile by the reference rasterizer on the host, then uploaded in one copy.
#include <vector>

#include "filter/atlas_source.hpp"
#include "reference/rasterizer.hpp"

namespace depthtrack {

namespace {
class HostAtlasSource final : public AtlasSource {
 public:
  HostAtlasSource(const Mesh& mesh, const Camera& camera, const TrackerConfig& config)
      : rasterizer_(mesh, camera, config.near_plane, config.observation.max_depth),
        pixels_(static_cast<size_t>(camera.pixel_count())) {}

  void draw(std::span<const Pose> poses, compute::Buffer<float>& atlas) override {
    host_.resize(poses.size() * pixels_);
    for (size_t i = 0; i < poses.size(); ++i)
      rasterizer_.render(poses[i], std::span<float>(host_.data() + i * pixels_, pixels_));
    atlas.upload(host_);
  }
  std::string description() const override { return "reference rasterizer on the host, uploaded"; }

 private:
  reference::Rasterizer rasterizer_;
  size_t pixels_;
  std::vector<float> host_;
};
}  // namespace

std::unique_ptr<AtlasSource> make_host_atlas_source(const Mesh& mesh, const Camera& camera,
                                                    const TrackerConfig& config) {
  return std::make_unique<HostAtlasSource>(mesh, camera, config);
}

}  // namespace depthtrack
