// The cl_khr_gl_sharing hand-off (src/interop/gl_sharing): chosen only when the device lists the
// extension, GL is EGL/GLX and the queue's context was made against it (tested with fake facts),
// and, where a platform offers it, delivering exactly what the staged copy delivers. A Device opens its
// GL trackers' context against its GL context on the same facts, and falls back, saying why, when the
// platform refuses.
#include <CL/cl_gl.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <iostream>
#include <sstream>

#include "atlas/gl_atlas_device.hpp"
#include "compute/opencl/cl_device_query.hpp"
#include "compute/opencl/cl_queue.hpp"
#include "compute/opencl/opencl_backend.hpp"
#include "compute/program_cache.hpp"
#include "device_support.hpp"
#include "interop/gl_shared_context_choice.hpp"
#include "interop/gl_sharing/gl_shared_queue.hpp"
#include "interop/gl_sharing/gl_sharing_choice.hpp"
#include "interop_support.hpp"

using namespace depthtrack;
using interop::choose_gl_sharing;
using render::GlNativeContext;

namespace {

// A CL_DEVICE_EXTENSIONS string as the device query splits it.
std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

int fake_display = 0, fake_context = 0;
const GlNativeContext egl{GlNativeContext::Api::Egl, &fake_display, &fake_context};
const GlNativeContext glx{GlNativeContext::Api::Glx, &fake_display, &fake_context};
const GlNativeContext osmesa{};
const auto platform = static_cast<cl_context_properties>(0x1234);

// A context's CL_CONTEXT_PROPERTIES: the platform, then `extra`, 0-terminated.
std::vector<cl_context_properties> made_with(std::vector<cl_context_properties> extra) {
  std::vector<cl_context_properties> p = {CL_CONTEXT_PLATFORM, platform};
  p.insert(p.end(), extra.begin(), extra.end());
  p.push_back(0);
  return p;
}

const std::string intel_like = "cl_khr_byte_addressable_store cl_khr_fp64 cl_khr_gl_sharing cl_khr_icd";
const std::string pocl_like = "cl_khr_byte_addressable_store cl_khr_fp64 cl_khr_icd cl_khr_gl_event";

}  // namespace

TEST_CASE("cl_khr_gl_sharing is chosen only when listed, with an EGL or GLX context the queue was made against",
          "[interop][gl_sharing]") {
  const auto shared_egl = made_with(interop::gl_sharing_properties(egl));
  SECTION("not listed (PoCL-like, or a look-alike name) gives the staged copy and says so") {
    for (const std::string& list : {pocl_like, std::string("cl_khr_gl_sharing_ext cl_khr_fp64"), std::string()}) {
      INFO(list);
      const auto choice = choose_gl_sharing(words(list), egl, shared_egl);
      CHECK_FALSE(choice.share);
      CHECK(choice.reason == "the OpenCL platform lacks cl_khr_gl_sharing");
    }
  }
  SECTION("listed, with the queue made against this EGL or GLX context, gives sharing") {
    const auto choice = choose_gl_sharing(words(intel_like), egl, shared_egl);
    CHECK(choice.share);
    CHECK(choice.reason.empty());
    CHECK(choose_gl_sharing(words(intel_like), glx, made_with(interop::gl_sharing_properties(glx))).share);
  }
  SECTION("listed, but the queue made before GL (the tracker's own queue) is told why not") {
    const auto choice = choose_gl_sharing(words(intel_like), egl, made_with({}));
    CHECK_FALSE(choice.share);
    CHECK(choice.reason.find("created before the GL context") != std::string::npos);
    int other = 0;
    const GlNativeContext another{GlNativeContext::Api::Egl, &fake_display, &other};
    CHECK_FALSE(choose_gl_sharing(words(intel_like), another, shared_egl).share);
    // The display must be the one of the context's own window system.
    CHECK_FALSE(choose_gl_sharing(words(intel_like), glx, shared_egl).share);
  }
  SECTION("listed, but an OSMesa context is told why not") {
    const auto choice = choose_gl_sharing(words(intel_like), osmesa, made_with({}));
    CHECK_FALSE(choice.share);
    CHECK(choice.reason.find("OSMesa") != std::string::npos);
  }
}

TEST_CASE("a Device opens its GL trackers' context against GL only for OpenCL listing cl_khr_gl_sharing, with EGL/GLX",
          "[interop][gl_sharing]") {
  using interop::choose_gl_shared_context;
  SECTION("OpenCL listing it, with an EGL or a GLX context: the context is opened against GL") {
    for (const GlNativeContext& gl : {egl, glx}) {
      const auto choice = choose_gl_shared_context(true, words(intel_like), gl);
      CHECK(choice.open_shared);
      CHECK(choice.reason.empty());
    }
    // ... and a queue on it then takes the sharing hand-off: the two choices agree on the same facts.
    CHECK(choose_gl_sharing(words(intel_like), egl, made_with(interop::gl_sharing_properties(egl))).share);
  }
  SECTION("PoCL-like (not listed) or a look-alike name: the Device's own context, and why") {
    for (const std::string& list : {pocl_like, std::string("cl_khr_gl_sharing_ext"), std::string()}) {
      INFO(list);
      const auto choice = choose_gl_shared_context(true, words(list), egl);
      CHECK_FALSE(choice.open_shared);
      CHECK(choice.reason == "the OpenCL platform lacks cl_khr_gl_sharing");
    }
  }
  SECTION("OSMesa: nothing to share, said so") {
    const auto choice = choose_gl_shared_context(true, words(intel_like), osmesa);
    CHECK_FALSE(choice.open_shared);
    CHECK(choice.reason.find("OSMesa") != std::string::npos);
  }
  SECTION("not OpenCL (CUDA, whose interop needs no shared context), even with the word listed") {
    const auto choice = choose_gl_shared_context(false, words(intel_like), egl);
    CHECK_FALSE(choice.open_shared);
    CHECK(choice.reason.find("not OpenCL") != std::string::npos);
  }
}

// PoCL's device with facts made to list cl_khr_gl_sharing: the Device tries a context against its GL
// context, PoCL refuses (its clGetGLContextInfoKHR names no device), and the GL trackers fall back to the
// Device's own context with the refusal in the hand-off's name. PoCL only: other platforms that do not list
// the extension are not known to survive the call (rusticl's crashed).
TEST_CASE("where the platform refuses a context against GL, the Device keeps its own and the hand-off says why",
          "[device][render][interop][gl_sharing]") {
  if (!test::gl_built()) return;
  const auto platforms = compute::opencl::platform_ids();
  const auto listed = compute::opencl::devices();
  const auto pocl = std::find_if(listed.begin(), listed.end(), [](const compute::DeviceInfo& d) {
    return d.platform == "Portable Computing Language";
  });
  if (pocl == listed.end()) {
    std::cout << "SKIPPED: no PoCL device to make list cl_khr_gl_sharing\n";
    return;
  }
  compute::DeviceInfo info = *pocl;
  if (info.gl_sharing) {
    std::cout << "SKIPPED: " << info.selector << " really lists cl_khr_gl_sharing (the case above tests it)\n";
    return;
  }
  unsigned p = 0, d = 0;
  REQUIRE(std::sscanf(info.selector.c_str(), "opencl:%u.%u", &p, &d) == 2);
  info.extensions.push_back("cl_khr_gl_sharing");
  info.gl_sharing = true;
  auto device = std::make_shared<compute::DeviceContext>(
      std::make_unique<compute::opencl::ClQueue>(platforms[p], compute::opencl::device_ids(platforms[p])[d], info));
  GlAtlasDevice gl;
  try {
    gl = open_gl_atlas_device(device, "auto");
  } catch (const BackendError& e) {
    std::cout << "SKIPPED: no GL context: " << e.what() << "\n";
    return;
  }
  INFO(info.selector << " " << info.name << ", GL " << gl.gl->describe());
  if (gl.gl->native().api == GlNativeContext::Api::None) {
    // OSMesa: not tried at all, so nothing was refused.
    CHECK(gl.compute == device);
    CHECK(gl.shared_context_refused.empty());
    return;
  }
  CHECK_FALSE(gl.shares_gl());
  CHECK(gl.compute == device);
  CHECK(gl.shared_context_refused.find("refused an OpenCL context against the GL context") != std::string::npos);
  render::AtlasRenderer renderer(*gl.gl, builtin_demo_mesh(), Camera::make(80, 60, 66, 66, 39.5, 29.5), 0.05, 6.0);
  renderer.reserve(1);
  const auto handoff = interop::make_atlas_handoff(*gl.compute->queue, renderer, gl.shared_context_refused);
  std::cout << info.selector << " told: " << handoff->name() << "\n";
  CHECK(handoff->name().rfind("staged copy", 0) == 0);
  CHECK(handoff->name().find(gl.shared_context_refused) != std::string::npos);
}

TEST_CASE("the OpenCL context properties that share a GL context name it and its display", "[interop][gl_sharing]") {
  const auto egl_properties = interop::gl_sharing_properties(egl);
  const std::vector<cl_context_properties> expected_egl = {
      CL_GL_CONTEXT_KHR, reinterpret_cast<cl_context_properties>(&fake_context), CL_EGL_DISPLAY_KHR,
      reinterpret_cast<cl_context_properties>(&fake_display)};
  CHECK(egl_properties == expected_egl);
  CHECK(interop::gl_sharing_properties(glx)[2] == CL_GLX_DISPLAY_KHR);
  CHECK_THROWS_AS(interop::gl_sharing_properties(osmesa), InputError);
}

// Runs where an OpenCL device lists cl_khr_gl_sharing and an EGL context can be made on its GPU
// (AMD, Intel, Mesa GPU drivers); nowhere on the project's machines (PoCL, NVIDIA's OpenCL).
TEST_CASE("where a platform lists cl_khr_gl_sharing, its hand-off is chosen and equals the staged copy",
          "[device][render][interop][gl_sharing]") {
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  std::string checked, failures;
  int tested = 0;
  for (const compute::DeviceInfo& device : compute::opencl::devices()) {
    checked += (checked.empty() ? "" : ", ") + device.platform + " (" + device.name + ")";
    if (!device.gl_sharing) continue;
    INFO(device.selector << " " << device.name);
    render::GlContextOptions options;
    options.device_uuid = device.uuid;
    std::unique_ptr<render::GlContext> context;
    std::unique_ptr<compute::Queue> shared;
    try {
      context = std::make_unique<render::GlContext>(options);
      shared = interop::open_gl_shared_queue(device, *context);
    } catch (const Error& e) {
      failures += "\n  " + device.selector + ": " + e.what();
      continue;
    }
    render::AtlasRenderer renderer(*context, builtin_demo_mesh(), camera, 0.05, 6.0, render::AtlasOptions{200});
    renderer.reserve(14);
    const auto best = interop::make_atlas_handoff(*shared, renderer);
    std::cout << device.selector << " hand-off: " << best->name() << "\n";
    REQUIRE(best->name().rfind("cl_khr_gl_sharing", 0) == 0);
    const auto particles = test::random_particles(14, 6);
    const std::vector<float> in_place = test::through(*best, *shared, renderer, particles);
    const std::vector<float> again = test::through(*best, *shared, renderer, particles);  // a second frame
    auto staged = interop::make_staged_handoff(*shared, renderer, "test");
    const std::vector<float> copied = test::through(*staged, *shared, renderer, particles);
    REQUIRE(in_place == copied);
    REQUIRE(again == copied);
    size_t covered = 0;
    for (float d : in_place) covered += d > 0;
    CHECK(covered > 14 * 100);
    // The tracker's own queue, opened before GL, is told why it gets the staged copy.
    const auto fallback = interop::make_atlas_handoff(*compute::open_device(device.selector), renderer);
    CHECK(fallback->name().find("created before the GL context") != std::string::npos);
    ++tested;
  }
  if (tested == 0)
    std::cout << "SKIPPED: no OpenCL platform here lists cl_khr_gl_sharing (checked: "
              << (checked.empty() ? "no OpenCL platform" : checked) << ")"
              << (failures.empty() ? "" : "; listed but unusable:" + failures) << "\n";
}
