#pragma once
// One way of getting a headless GL context (EGL device, EGL surfaceless, OSMesa). Each create_*
// either returns a context that is current on the calling thread or throws BackendError saying why.
#include <array>
#include <memory>
#include <optional>
#include <string>

#include "atlas/gl/gl_native.hpp"
#include "atlas/gl/gl_proc.hpp"

namespace depthtrack::render {

struct GlVersion {
  int major = 3, minor = 3;
};

class GlPlatform {
 public:
  virtual ~GlPlatform() = default;
  virtual void make_current() = 0;
  virtual GlProcLoader loader() const = 0;
  // "EGL device 0", "EGL surfaceless", "OSMesa".
  virtual std::string name() const = 0;
  // The handles another API shares the context by; Api::None where it cannot (OSMesa).
  virtual GlNativeContext native() const { return {}; }
};

// Tries the devices from `device` on (default: all, first that works; the one whose UUID is
// `uuid` first where EGL reports UUIDs).
std::unique_ptr<GlPlatform> create_egl_device_platform(std::optional<int> device, GlVersion required,
                                                       const std::optional<std::array<unsigned char, 16>>& uuid);
std::unique_ptr<GlPlatform> create_egl_surfaceless_platform(GlVersion required);
// Throws when the library was built without OSMesa.
std::unique_ptr<GlPlatform> create_osmesa_platform(GlVersion required);

}  // namespace depthtrack::render
