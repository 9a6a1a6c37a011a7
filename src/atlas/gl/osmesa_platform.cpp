// OSMesa path: Mesa's off-screen library, for machines whose EGL cannot give a context. It insists
// on a bound colour buffer, so a 1x1 one is kept; all rendering goes to FBOs.
#include <depthtrack/error.hpp>
#include <string>

#include "atlas/gl/gl_platform.hpp"

#ifdef DEPTHTRACK_WITH_OSMESA
#include <GL/osmesa.h>

#include <array>

namespace depthtrack::render {
namespace {

GlProc osmesa_loader(const char* name) {
  return OSMesaGetProcAddress(name);
}

class OsmesaPlatform final : public GlPlatform {
 public:
  explicit OsmesaPlatform(GlVersion required) {
    std::string tried;
    for (const GlVersion v : {GlVersion{4, 5}, required}) {
      if (v.major < required.major || (v.major == required.major && v.minor < required.minor)) continue;
      const int attributes[] = {OSMESA_FORMAT,
                                OSMESA_RGBA,
                                OSMESA_DEPTH_BITS,
                                0,
                                OSMESA_PROFILE,
                                OSMESA_CORE_PROFILE,
                                OSMESA_CONTEXT_MAJOR_VERSION,
                                v.major,
                                OSMESA_CONTEXT_MINOR_VERSION,
                                v.minor,
                                0};
      context_ = OSMesaCreateContextAttribs(attributes, nullptr);
      if (context_) break;
      tried += (tried.empty() ? "" : ", ") + std::to_string(v.major) + "." + std::to_string(v.minor) + " core";
    }
    if (!context_) throw BackendError("OSMesaCreateContextAttribs returned null for GL " + tried);
    make_current();
  }
  ~OsmesaPlatform() override { OSMesaDestroyContext(context_); }
  void make_current() override {
    if (!OSMesaMakeCurrent(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw BackendError("OSMesaMakeCurrent failed");
  }
  GlProcLoader loader() const override { return &osmesa_loader; }
  std::string name() const override { return "OSMesa"; }

 private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> pixel_{};
};

}  // namespace

std::unique_ptr<GlPlatform> create_osmesa_platform(GlVersion required) {
  return std::make_unique<OsmesaPlatform>(required);
}

}  // namespace depthtrack::render
#else
namespace depthtrack::render {
std::unique_ptr<GlPlatform> create_osmesa_platform(GlVersion) {
  throw BackendError("not built in (libOSMesa was not found when depthtrack was configured)");
}
}  // namespace depthtrack::render
#endif
