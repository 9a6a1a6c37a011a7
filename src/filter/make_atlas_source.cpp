// The atlas source TrackerConfig::renderer names.
#include <depthtrack/error.hpp>

#include "filter/atlas_source.hpp"

namespace depthtrack {

std::unique_ptr<AtlasSource> make_host_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                    const TrackerConfig& config);
std::unique_ptr<AtlasSource> make_gl_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                  const TrackerConfig& config);
std::unique_ptr<AtlasSource> make_kernel_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                      const TrackerConfig& config);

std::unique_ptr<AtlasSource> make_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                               const TrackerConfig& config) {
  if (config.renderer == "cpu") return make_host_atlas_source(queue, mesh, camera, config);
  if (config.renderer == "gl") return make_gl_atlas_source(queue, mesh, camera, config);
  if (config.renderer == "kernel") return make_kernel_atlas_source(queue, mesh, camera, config);
  throw InputError("unknown renderer '" + config.renderer + "' (choose cpu, gl or kernel)");
}

}  // namespace depthtrack
