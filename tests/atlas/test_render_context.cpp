// Headless GL contexts: every path that exists here comes up and says what it is; a bad GL path
// name and a context no path can give fail with messages that say why.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <depthtrack/error.hpp>
#include <iostream>
#include <optional>
#include <string>

#include "atlas/gl/gl_context.hpp"

using namespace depthtrack;
using render::GlContext;
using render::GlPath;

namespace {
// Sets an environment variable for one scope, restoring the previous value after.
render::GlContextOptions options(std::optional<GlPath> path, int major = 3, int minor = 3,
                                 std::optional<int> device = std::nullopt) {
  render::GlContextOptions o;
  o.path = path;
  o.major = major;
  o.minor = minor;
  o.device = device;
  return o;
}

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? setenv(name, value, 1) : unsetenv(name);
  }
  ~ScopedEnv() { old_ ? setenv(name_, old_->c_str(), 1) : unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};
}  // namespace

TEST_CASE("each headless GL path gives a core context and describes itself", "[render]") {
  int paths_run = 0;
  for (GlPath path : {GlPath::EglDevice, GlPath::EglSurfaceless, GlPath::OSMesa}) {
    try {
      GlContext context(options(path));
      ++paths_run;
      std::cout << GlContext::path_name(path) << ": " << context.describe() << "\n";
      CHECK(context.path() == path);
      CHECK(context.max_render_size() >= 4096);
      CHECK(context.describe().find("GL_MAX_TEXTURE_SIZE") != std::string::npos);
    } catch (const BackendError& e) {
      std::cout << "note: " << GlContext::path_name(path) << " unavailable: " << e.what() << "\n";
    }
  }
  if (paths_run == 0) std::cout << "SKIPPED: no headless GL path could be opened\n";
}

TEST_CASE("a named GL path restricts the search and nonsense is refused naming the choices", "[render]") {
  // TrackerConfig::gl_path's spellings (the command fills it from --gl or DEPTHTRACK_GL).
  CHECK(!GlContext::path_from_name("auto"));
  for (GlPath path : {GlPath::EglDevice, GlPath::EglSurfaceless, GlPath::OSMesa})
    CHECK(GlContext::path_from_name(GlContext::path_name(path)) == path);
  try {
    GlContext::path_from_name("nonsense");
    FAIL("the GL path 'nonsense' was accepted");
  } catch (const InputError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("nonsense") != std::string::npos);
    for (const char* choice : {"egl-device", "egl-surfaceless", "osmesa"})
      CHECK(message.find(choice) != std::string::npos);
  }
  // The library ignores DEPTHTRACK_GL: only the options choose.
  ScopedEnv env("DEPTHTRACK_GL", "nonsense");
  try {
    GlContext context(options(GlContext::path_from_name("egl-surfaceless")));
    CHECK(context.path() == GlPath::EglSurfaceless);
  } catch (const BackendError& e) {
    std::cout << "SKIPPED: egl-surfaceless: " << e.what() << "\n";
  }
}

TEST_CASE("when every GL path fails the error lists each path and its reason", "[render]") {
  ScopedEnv env("DEPTHTRACK_GL", nullptr);
  try {
    GlContext context(options(std::nullopt, 9, 9));  // no GL offers 9.9
    FAIL("a GL 9.9 context was created");
  } catch (const BackendError& e) {
    const std::string message = e.what();
    std::cout << message << "\n";
    for (const char* path : {"egl-device: ", "egl-surfaceless: ", "osmesa: "})
      CHECK(message.find(path) != std::string::npos);
    CHECK(message.find("9.9") != std::string::npos);
  }
  try {
    GlContext context(options(GlPath::EglDevice, 3, 3, 99));
    FAIL("EGL device 99 was accepted");
  } catch (const BackendError& e) {
    CHECK(std::string(e.what()).find("EGL device 99 requested") != std::string::npos);
  }
}
