#include "atlas/gl/gl_context.hpp"

#include <algorithm>
#include <cstdlib>
#include <depthtrack/error.hpp>
#include <sstream>
#include <vector>

#include "atlas/gl/gl_platform.hpp"

namespace depthtrack::render {
namespace {

constexpr GlPath all_paths[] = {GlPath::EglDevice, GlPath::EglSurfaceless, GlPath::OSMesa};

std::unique_ptr<GlPlatform> create(GlPath path, const GlContextOptions& options) {
  const GlVersion required{options.major, options.minor};
  switch (path) {
    case GlPath::EglDevice:
      return create_egl_device_platform(options.device, required, options.device_uuid);
    case GlPath::EglSurfaceless:
      return create_egl_surfaceless_platform(required);
    case GlPath::OSMesa:
      return create_osmesa_platform(required);
  }
  throw BackendError("unknown GL path");
}

std::string gl_string(const GlFunctions& gl, GLenum name) {
  const GLubyte* s = gl.GetString(name);
  return s ? reinterpret_cast<const char*>(s) : "?";
}

}  // namespace

const char* GlContext::path_name(GlPath path) {
  switch (path) {
    case GlPath::EglDevice:
      return "egl-device";
    case GlPath::EglSurfaceless:
      return "egl-surfaceless";
    case GlPath::OSMesa:
      return "osmesa";
  }
  return "?";
}

std::optional<GlPath> GlContext::path_from_name(const std::string& name) {
  if (name == "auto") return std::nullopt;
  for (GlPath p : all_paths)
    if (name == path_name(p)) return p;
  throw InputError("'" + name +
                   "' is not a GL path; valid choices: egl-device, egl-surfaceless, osmesa (or auto for all in turn)");
}

GlContextOptions GlContextOptions::for_device(const std::optional<std::array<unsigned char, 16>>& uuid,
                                              const std::string& gl_path) {
  GlContextOptions options;
  options.device_uuid = uuid;
  options.path = GlContext::path_from_name(gl_path);
  return options;
}

GlContext::GlContext(const GlContextOptions& options) {
  std::vector<GlPath> paths(std::begin(all_paths), std::end(all_paths));
  if (options.path) paths = {*options.path};
  std::string reasons;
  for (GlPath p : paths) {
    try {
      auto platform = create(p, options);
      GlFunctions gl;
      if (const char* missing = load_gl_functions(gl, platform->loader()))
        throw BackendError(std::string("GL entry point ") + missing + " not found");
      platform_ = std::move(platform);
      gl_ = gl;
      path_ = p;
      break;
    } catch (const BackendError& e) {
      reasons += std::string("\n  ") + path_name(p) + ": " + e.what();
    }
  }
  if (!platform_)
    throw BackendError("no headless OpenGL " + std::to_string(options.major) + "." + std::to_string(options.minor) +
                       " core context could be created; tried:" + reasons);
  GLint max_texture = 0, max_viewports = 0, viewport_dims[2] = {0, 0};
  gl_.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
  gl_.GetIntegerv(GL_MAX_VIEWPORTS, &max_viewports);  // GL 4.1; stays 0 (or errors) before
  gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport_dims);
  while (gl_.GetError() != GL_NO_ERROR) {
  }
  max_render_size_ = std::min({max_texture, viewport_dims[0], viewport_dims[1]});
  std::ostringstream d;
  d << platform_->name() << ": " << gl_string(gl_, GL_VENDOR) << ", " << gl_string(gl_, GL_RENDERER) << ", GL "
    << gl_string(gl_, GL_VERSION) << ", GL_MAX_TEXTURE_SIZE " << max_texture << ", GL_MAX_VIEWPORTS " << max_viewports;
  description_ = d.str();
}

GlContext::~GlContext() = default;

bool GlContext::has_extension(const std::string& name) const {
  GLint count = 0;
  gl_.GetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* extension = reinterpret_cast<const char*>(gl_.GetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (extension && name == extension) return true;
  }
  return false;
}

GlProc GlContext::proc_address(const char* name) const {
  return platform_->loader()(name);
}

GlNativeContext GlContext::native() const {
  return platform_->native();
}

void GlContext::make_current() {
  platform_->make_current();
}

}  // namespace depthtrack::render
