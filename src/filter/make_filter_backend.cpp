#include <depthtrack/error.hpp>

#include "filter/filter_backend.hpp"
#include "reference/reference_filter.hpp"

namespace depthtrack {

std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config) {
  if (config.backend == "reference") return std::make_unique<reference::ReferenceFilter>(mesh, working_camera, config);
  throw InputError("unknown backend '" + config.backend + "'; available: reference");
}

}  // namespace depthtrack
