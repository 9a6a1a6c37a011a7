#pragma once
// The filter backends' factory: the tracker layer is the one that knows both implementations.
#include <depthtrack/camera.hpp>
#include <depthtrack/device.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker_config.hpp>
#include <memory>
#include <string>

#include "model/filter_backend.hpp"

namespace depthtrack {

// The device a TrackerConfig::backend string names (empty: reference); InputError
// listing the names otherwise, saying when the name came from the environment.
std::shared_ptr<Device> open_config_device(const TrackerConfig& config);
// The filter on `device`: the reference (on a thread pool for cpu) or the device filter on its queue.
std::unique_ptr<FilterBackend> make_filter_backend(const Device& device, const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config);
// The same on a device of its own, opened from config.backend.
std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config);
// cpu: the hardware's threads; cpu:N: N of them (1 to 1024); InputError otherwise.
int cpu_backend_threads(const std::string& backend);

}  // namespace depthtrack
