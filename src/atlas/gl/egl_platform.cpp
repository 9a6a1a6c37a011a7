// EGL paths: the device platform (EGL_EXT_platform_device) and Mesa's surfaceless platform. Both
// render only into FBOs, so the context is made current without a surface
// (EGL_KHR_surfaceless_context) and no config is needed beyond one that supports desktop GL.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <depthtrack/error.hpp>
#include <string>
#include <vector>

#include "atlas/gl/gl_platform.hpp"

namespace depthtrack::render {
namespace {

std::string egl_error_name(EGLint error) {
  switch (error) {
#define NAME(e) \
  case e:       \
    return #e;
    NAME(EGL_SUCCESS)
    NAME(EGL_NOT_INITIALIZED)
    NAME(EGL_BAD_ACCESS)
        NAME(EGL_BAD_ALLOC) NAME(EGL_BAD_ATTRIBUTE) NAME(EGL_BAD_CONFIG) NAME(EGL_BAD_CONTEXT)
            NAME(EGL_BAD_CURRENT_SURFACE) NAME(EGL_BAD_DISPLAY) NAME(EGL_BAD_MATCH) NAME(EGL_BAD_NATIVE_PIXMAP)
                NAME(EGL_BAD_NATIVE_WINDOW) NAME(EGL_BAD_PARAMETER) NAME(EGL_BAD_SURFACE) NAME(EGL_CONTEXT_LOST)
#undef NAME
                    default : return "unknown EGL error " +
                              std::to_string(error);
  }
}

[[noreturn]] void fail(const std::string& call) {
  throw BackendError(call + " failed: " + egl_error_name(eglGetError()));
}

GlProc egl_loader(const char* name) {
  return eglGetProcAddress(name);
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

template <typename F>
F egl_proc(const char* name) {
  auto f = reinterpret_cast<F>(eglGetProcAddress(name));
  if (!f) throw BackendError(std::string("eglGetProcAddress(\"") + name + "\") returned null");
  return f;
}

class EglPlatform final : public GlPlatform {
 public:
  // Initialises the display and creates a core context of at least `required` (4.5 when possible).
  EglPlatform(EGLDisplay display, std::string name, GlVersion required) : display_(display), name_(std::move(name)) {
    if (display_ == EGL_NO_DISPLAY) fail("eglGetPlatformDisplayEXT");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor)) fail("eglInitialize");
    // Not eglTerminate'd on failure or in the destructor: displays are per-device singletons that
    // another GlContext in the process may still use.
    if (!has_extension(eglQueryString(display_, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
      throw BackendError("display lacks EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");
    const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attributes, &config, 1, &count)) fail("eglChooseConfig");
    if (count == 0) throw BackendError("eglChooseConfig found no config with EGL_OPENGL_BIT");
    std::vector<GlVersion> versions{{4, 5}};
    if (required.major != 4 || required.minor != 5) versions.push_back(required);
    std::string tried;
    for (const GlVersion v : versions) {
      if (v.major < required.major || (v.major == required.major && v.minor < required.minor)) continue;
      const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                           v.major,
                                           EGL_CONTEXT_MINOR_VERSION,
                                           v.minor,
                                           EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                           EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                           EGL_NONE};
      context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attributes);
      if (context_ != EGL_NO_CONTEXT) break;
      tried += (tried.empty() ? "" : ", ") + std::to_string(v.major) + "." + std::to_string(v.minor) +
               " core: " + egl_error_name(eglGetError());
    }
    if (context_ == EGL_NO_CONTEXT) throw BackendError("eglCreateContext failed for GL " + tried);
    make_current();
  }
  ~EglPlatform() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }
  void make_current() override {
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) fail("eglMakeCurrent");
  }
  GlProcLoader loader() const override { return &egl_loader; }
  std::string name() const override { return name_; }
  GlNativeContext native() const override { return {GlNativeContext::Api::Egl, display_, context_}; }

 private:
  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string name_;
};

void require_client_extension(const char* name) {
  if (!has_extension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), name))
    throw BackendError(std::string("EGL client extensions lack ") + name);
}

// Whether EGL device `device` reports `uuid` (EGL_EXT_device_persistent_id).
bool has_uuid(EGLDeviceEXT device, const std::array<unsigned char, 16>& uuid) {
  auto query_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  auto query_binary = reinterpret_cast<PFNEGLQUERYDEVICEBINARYEXTPROC>(eglGetProcAddress("eglQueryDeviceBinaryEXT"));
  if (!query_string || !query_binary ||
      !has_extension(query_string(device, EGL_EXTENSIONS), "EGL_EXT_device_persistent_id"))
    return false;
  std::array<unsigned char, 16> found{};
  EGLint size = 0;
  return query_binary(device, EGL_DEVICE_UUID_EXT, static_cast<EGLint>(found.size()), found.data(), &size) &&
         size == static_cast<EGLint>(found.size()) && found == uuid;
}

}  // namespace

std::unique_ptr<GlPlatform> create_egl_device_platform(std::optional<int> device, GlVersion required,
                                                       const std::optional<std::array<unsigned char, 16>>& uuid) {
  require_client_extension("EGL_EXT_platform_device");
  auto query_devices = egl_proc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto get_display = egl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  EGLint count = 0;
  if (!query_devices(0, nullptr, &count)) fail("eglQueryDevicesEXT");
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  if (!query_devices(count, devices.data(), &count)) fail("eglQueryDevicesEXT");
  if (count == 0) throw BackendError("eglQueryDevicesEXT found no device");
  if (device && (*device < 0 || *device >= count))
    throw BackendError("EGL device " + std::to_string(*device) + " requested, " + std::to_string(count) + " present");
  std::vector<int> order;
  for (int i = device.value_or(0); i < (device ? *device + 1 : count); ++i) order.push_back(i);
  int same_gpu = -1;
  for (int i : order)
    if (uuid && same_gpu < 0 && has_uuid(devices[static_cast<size_t>(i)], *uuid)) same_gpu = i;
  if (same_gpu >= 0) std::stable_partition(order.begin(), order.end(), [&](int i) { return i == same_gpu; });
  std::string reasons;
  for (int i : order) {
    try {
      EGLDisplay display = get_display(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<size_t>(i)], nullptr);
      const std::string name =
          "EGL device " + std::to_string(i) + (i == same_gpu ? " (the compute device's GPU, by UUID)" : "");
      return std::make_unique<EglPlatform>(display, name, required);
    } catch (const BackendError& e) {
      reasons += (reasons.empty() ? "" : "; ") + ("device " + std::to_string(i) + ": ") + e.what();
    }
  }
  throw BackendError(reasons);
}

std::unique_ptr<GlPlatform> create_egl_surfaceless_platform(GlVersion required) {
  require_client_extension("EGL_MESA_platform_surfaceless");
  auto get_display = egl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  EGLDisplay display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  return std::make_unique<EglPlatform>(display, "EGL surfaceless", required);
}

}  // namespace depthtrack::render
