#pragma once
// A headless OpenGL core context (>= 3.3, 4.5 where offered), made current on the constructing
// thread. Paths, in order: EGL device platform, EGL surfaceless (Mesa), OSMesa; GlContextOptions::path
// (TrackerConfig::gl_path) restricts the search to one. No window, no X server:
// everything renders into framebuffer objects.
#include <array>
#include <memory>
#include <optional>
#include <string>

#include "atlas/gl/gl_functions.hpp"
#include "atlas/gl/gl_native.hpp"

namespace depthtrack::render {

class GlPlatform;

enum class GlPath { EglDevice, EglSurfaceless, OSMesa };

struct GlContextOptions {
  std::optional<GlPath> path;  // only this path; unset: all in order
  std::optional<int> device;   // EGL device index; unset: the first that works
  // Prefer the EGL device with this UUID (EGL_EXT_device_persistent_id): the compute device's GPU.
  std::optional<std::array<unsigned char, 16>> device_uuid;
  int major = 3, minor = 3;  // the least core version accepted

  // The GL context for a compute device: on its GPU where EGL can tell (`uuid`), on the one path
  // `gl_path` names unless it is "auto" (GlContext::path_from_name; InputError for another word).
  static GlContextOptions for_device(const std::optional<std::array<unsigned char, 16>>& uuid,
                                     const std::string& gl_path);
};

class GlContext {
 public:
  explicit GlContext(const GlContextOptions& options = {});
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes this context current on the calling thread (several contexts may live in one process).
  void make_current();
  const GlFunctions& gl() const { return gl_; }
  GlPath path() const { return path_; }
  // Path, GL_VENDOR, GL_RENDERER, GL_VERSION, GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORTS on one line.
  std::string describe() const { return description_; }
  // The largest square render target: min(GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORT_DIMS).
  int max_render_size() const { return max_render_size_; }

  // Whether GL_EXTENSIONS lists `name`; an entry point of an extension (null when unknown).
  bool has_extension(const std::string& name) const;
  GlProc proc_address(const char* name) const;
  // The EGL display and context (for cl_khr_gl_sharing); Api::None for OSMesa.
  GlNativeContext native() const;

  // "egl-device", "egl-surfaceless", "osmesa": the TrackerConfig::gl_path spellings.
  static const char* path_name(GlPath path);
  // A gl_path parsed ("auto": unset); InputError naming the valid choices for anything else.
  static std::optional<GlPath> path_from_name(const std::string& name);

 private:
  std::unique_ptr<GlPlatform> platform_;
  GlFunctions gl_;
  GlPath path_ = GlPath::EglDevice;
  std::string description_;
  int max_render_size_ = 0;
};

}  // namespace depthtrack::render
