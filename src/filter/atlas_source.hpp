#pragma once
// Where the device filter's pose atlas comes from: particles x pixels metric depths in a device
// buffer, tile i = particle i, row-major, 0 = not covered. Each source also reports its hand-off.
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <memory>
#include <span>
#include <string>

#include "compute/buffer.hpp"

namespace depthtrack {

class AtlasSource {
 public:
  virtual ~AtlasSource() = default;
  virtual void draw(std::span<const Pose> poses, compute::Buffer<float>& atlas) = 0;
  // e.g. "GL (EGL device 0: ...), staged copy" or "reference rasterizer on the host, upload".
  virtual std::string description() const = 0;
};

// The source TrackerConfig::renderer names: "cpu" (the reference rasterizer on the host) or "gl"
// (the OpenGL atlas renderer; BackendError naming every GL path tried when none works).
std::unique_ptr<AtlasSource> make_atlas_source(const Mesh& mesh, const Camera& camera, const TrackerConfig& config);

}  // namespace depthtrack
