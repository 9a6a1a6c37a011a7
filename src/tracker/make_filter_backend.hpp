#pragma once
// The filter backends' factory: the tracker layer is the one that knows both implementations.
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker_config.hpp>
#include <memory>

#include "model/filter_backend.hpp"

namespace depthtrack {

// The backend a TrackerConfig::backend string names; InputError listing the names otherwise.
std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config);

}  // namespace depthtrack
