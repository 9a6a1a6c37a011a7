#pragma once
// The library's side of a Device, which its public header keeps private: the compute context its filters
// run on and the GL sides its GL trackers draw with. Every Device is an OpenDevice (Device::open makes it).
#include <depthtrack/device.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>

#include "atlas/gl_atlas_device.hpp"
#include "compute/program_cache.hpp"

namespace depthtrack {

class OpenDevice final : public Device {
 public:
  OpenDevice(std::string opened, std::shared_ptr<compute::DeviceContext> device_context);
  ~OpenDevice() override;

  const std::string opened_selector;
  // The compute queue and program cache; nullptr for a host Device.
  const std::shared_ptr<compute::DeviceContext> compute_context;
  // For a GL tracker on a compute Device: the GL context for `gl_path` (TrackerConfig::gl_path) on the
  // calling thread, made on the first call, and the compute context to run on. BackendError when no GL
  // context can be made (nothing is kept: a later call tries again); InputError for a host Device.
  GlAtlasDevice gl_atlas(const std::string& gl_path) const;
  size_t gl_contexts() const;
  size_t program_builds() const;

 private:
  struct GlKey {
    std::string path;
    std::thread::id thread;
    bool operator<(const GlKey& o) const { return std::tie(path, thread) < std::tie(o.path, o.thread); }
  };
  mutable std::mutex mutex_;                   // guards gl_
  mutable std::map<GlKey, GlAtlasDevice> gl_;  // the GL sides made so far, by GL path and thread
};

// The library's way in from a public Device.
struct DeviceAccess {
  static const OpenDevice& of(const Device& device) { return static_cast<const OpenDevice&>(device); }
  // The compute queue and program cache; nullptr for a host Device.
  static const std::shared_ptr<compute::DeviceContext>& context(const Device& device) {
    return of(device).compute_context;
  }
  // OpenDevice::gl_atlas.
  static GlAtlasDevice gl_atlas(const Device& device, const std::string& gl_path) {
    return of(device).gl_atlas(gl_path);
  }
};

}  // namespace depthtrack
