// The atlas source TrackerConfig::renderer names.
#include <depthtrack/error.hpp>

#include "atlas/atlas_source.hpp"
#include "atlas/gl_atlas_device.hpp"

namespace depthtrack {

std::unique_ptr<AtlasSource> make_host_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                    const TrackerConfig& config);
#ifdef DEPTHTRACK_WITH_GL
std::unique_ptr<AtlasSource> make_gl_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                  const TrackerConfig& config, const GlAtlasDevice* gl);
#else
const char* const kGlNotBuilt = "the gl renderer was not built (DEPTHTRACK_WITH_GL=OFF); choose cpu or kernel";
std::unique_ptr<AtlasSource> make_gl_atlas_source(compute::Queue&, const Mesh&, const Camera&, const TrackerConfig&,
                                                  const GlAtlasDevice*) {
  throw InputError(kGlNotBuilt);
}
GlAtlasDevice open_gl_atlas_device(const std::shared_ptr<compute::DeviceContext>&, const std::string&) {
  throw InputError(kGlNotBuilt);
}
#endif
std::unique_ptr<AtlasSource> make_kernel_atlas_source(compute::Queue& queue, compute::ProgramCache& programs,
                                                      const Mesh& mesh, const Camera& camera,
                                                      const TrackerConfig& config);

compute::EventPtr AtlasSource::draw_range(const compute::Buffer<float>&, compute::Buffer<float>&, size_t, size_t) {
  throw InputError("this atlas source draws every particle's tile at once, not in turns");
}

std::unique_ptr<AtlasSource> make_atlas_source(compute::ProgramCache& programs, const Mesh& mesh, const Camera& camera,
                                               const TrackerConfig& config) {
  return make_atlas_source(programs.queue(), programs, mesh, camera, config);
}

std::unique_ptr<AtlasSource> make_atlas_source(compute::Queue& queue, compute::ProgramCache& programs, const Mesh& mesh,
                                               const Camera& camera, const TrackerConfig& config,
                                               const GlAtlasDevice* gl) {
  switch (config.renderer) {
    case Renderer::Cpu:
      return make_host_atlas_source(queue, mesh, camera, config);
    case Renderer::Gl:
      return make_gl_atlas_source(queue, mesh, camera, config, gl);
    case Renderer::Kernel:
      return make_kernel_atlas_source(queue, programs, mesh, camera, config);
  }
  throw InputError("unknown renderer " + std::to_string(static_cast<int>(config.renderer)) +
                   " (choose cpu, gl or kernel)");
}

}  // namespace depthtrack
