// The atlas drawn by OpenGL in one instanced call per page, handed to the compute backend by a
// staged copy (read back to the host, uploaded). Zero-copy hand-offs (CUDA-GL interop,
// cl_khr_gl_sharing) are the next step; this path works on every platform, PoCL + llvmpipe included.
#include <depthtrack/error.hpp>
#include <vector>

#include "filter/atlas_source.hpp"
#include "render/atlas_renderer.hpp"

namespace depthtrack {

namespace {
class GlAtlasSource final : public AtlasSource {
 public:
  GlAtlasSource(const Mesh& mesh, const Camera& camera, const TrackerConfig& config)
      : context_(),
        renderer_(context_, mesh, camera, config.near_plane, config.observation.max_depth),
        pixels_(static_cast<size_t>(camera.pixel_count())) {}

  void draw(std::span<const Pose> poses, compute::Buffer<float>& atlas) override {
    renderer_.render(poses);
    host_.resize(poses.size() * pixels_);
    renderer_.read_back(host_);
    atlas.upload(host_);
  }
  std::string description() const override { return "GL (" + context_.describe() + "), staged copy"; }

 private:
  render::GlContext context_;
  render::AtlasRenderer renderer_;
  size_t pixels_;
  std::vector<float> host_;
};
}  // namespace

std::unique_ptr<AtlasSource> make_host_atlas_source(const Mesh& mesh, const Camera& camera,
                                                    const TrackerConfig& config);

std::unique_ptr<AtlasSource> make_atlas_source(const Mesh& mesh, const Camera& camera, const TrackerConfig& config) {
  if (config.renderer == "cpu") return make_host_atlas_source(mesh, camera, config);
  if (config.renderer == "gl") return std::make_unique<GlAtlasSource>(mesh, camera, config);
  throw InputError("unknown renderer '" + config.renderer + "' (choose cpu or gl)");
}

}  // namespace depthtrack
