// depthtrack info: every compute device of every backend, and what it offers depthtrack.
#include <cstdio>
#include <depthtrack/camera.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/environment_defaults.hpp"
#include "compute/backend.hpp"
#include "compute/format_bytes.hpp"
#include "compute/queue.hpp"
#include "core/thread_pool.hpp"
#include "io/device_info_json.hpp"
#ifdef DEPTHTRACK_WITH_GL
#include "atlas/gl/atlas_renderer.hpp"
#include "atlas/gl/gl_context.hpp"
#include "atlas/gl_atlas_device.hpp"
#include "compute/program_cache.hpp"
#include "interop/atlas_handoff.hpp"
#endif

namespace depthtrack::cli {

namespace {
using depthtrack::compute::format_bytes;

const char* yes_no(bool value) {
  return value ? "yes" : "no";
}

void print_extensions(const std::vector<std::string>& extensions) {
  std::printf("    %-18s", "extensions");
  if (extensions.empty()) std::printf("(none listed)");
  size_t column = 0;
  for (const auto& extension : extensions) {
    if (column > 0 && column + extension.size() > 80) {  // wrap under the first one
      std::printf("\n    %-18s", "");
      column = 0;
    }
    std::printf("%s ", extension.c_str());
    column += extension.size() + 1;
  }
  std::printf("\n");
}

// The GL context the tracker's GL renderer would use with this device, and the hand-off it gets:
// found by setting both up for a one-tile atlas as a Device does for its GL trackers (the GL context
// first, then the compute context against it where the platform shares GL), so what is reported is what
// happens.
struct AtlasPath {
  std::string context, handoff, unavailable;  // unavailable: why not (first line), else empty
};

#ifndef DEPTHTRACK_WITH_GL
const char* const kNoGl = "the GL atlas was not built (DEPTHTRACK_WITH_GL=OFF)";
#endif

AtlasPath find_atlas_path([[maybe_unused]] const compute::DeviceInfo& d) {
#ifndef DEPTHTRACK_WITH_GL
  return {"", "", kNoGl};
#else
  try {
    const auto device = std::make_shared<compute::DeviceContext>(compute::open_device(d.selector));
    // The GL path as demo and track would take it.
    const GlAtlasDevice gl = open_gl_atlas_device(device, gl_path_from_environment());
    render::AtlasRenderer renderer(*gl.gl, builtin_demo_mesh(), Camera::make(80, 60, 66, 66, 39.5, 29.5), 0.05, 6);
    renderer.reserve(1);
    const auto handoff = interop::make_atlas_handoff(*gl.compute->queue, renderer, gl.shared_context_refused);
    return {gl.gl->describe(), handoff->name(), ""};
  } catch (const Error& e) {
    const std::string message = e.what();
    return {"", "", message.substr(0, message.find('\n'))};
  }
#endif
}

void print_atlas_path(const compute::DeviceInfo& d) {
  const AtlasPath path = find_atlas_path(d);
  if (!path.unavailable.empty()) {
    std::printf("    %-18sunavailable: %s\n", "atlas GL", path.unavailable.c_str());
    return;
  }
  std::printf("    %-18s%s\n", "atlas GL", path.context.c_str());
  std::printf("    %-18s%s\n", "atlas hand-off", path.handoff.c_str());
}

void print_device(const compute::DeviceInfo& d, bool extensions) {
  std::printf("  %s  %s\n", d.selector.c_str(), d.name.c_str());
  std::printf("    %-18s%s\n", "platform", d.platform.c_str());
  std::printf("    %-18s%s\n", "vendor", d.vendor.c_str());
  std::printf("    %-18s%s\n", "driver", d.driver.c_str());
  std::printf("    %-18s%s\n", "version", d.version.c_str());
  std::printf("    %-18s%s\n", "type", d.is_gpu ? "GPU" : "CPU or other");
  std::printf("    %-18s%s\n", "global memory", format_bytes(d.global_memory).c_str());
  std::printf("    %-18s%s\n", "max allocation", format_bytes(d.max_allocation).c_str());
  std::printf("    %-18s%s\n", "local memory", format_bytes(d.local_memory).c_str());
  std::printf("    %-18s%zu\n", "max work-group", d.max_work_group_size);
  std::printf("    %-18s%d\n", "compute units", d.compute_units);
  std::printf("    %-18s%s\n", "gl_sharing", yes_no(d.gl_sharing));
  std::printf("    %-18s%s\n", "external memory", yes_no(d.external_memory));
  std::printf("    %-18s%s\n", "fp64", yes_no(d.fp64));
  std::printf("    %-18s%s\n", "subgroups", yes_no(d.subgroups));
  std::printf("    %-18s%s\n", "int64 atomics", yes_no(d.int64_atomics));
  print_atlas_path(d);
  if (extensions) print_extensions(d.extensions);
}

// A headless GL path: its context and atlas page size, or why it is unavailable.
struct GlPathFacts {
  const char* name;
  std::string context, unavailable;
  int max_render_size = 0;
};

std::vector<GlPathFacts> gl_paths() {
  std::vector<GlPathFacts> facts;
#ifndef DEPTHTRACK_WITH_GL
  facts.push_back({"gl", "", kNoGl, 0});
#else
  for (auto path : {render::GlPath::EglDevice, render::GlPath::EglSurfaceless, render::GlPath::OSMesa}) {
    GlPathFacts f{render::GlContext::path_name(path), "", "", 0};
    try {
      render::GlContextOptions options;
      options.path = path;
      const render::GlContext context(options);
      f.context = context.describe();
      f.max_render_size = context.max_render_size();
    } catch (const Error& e) {
      const std::string message = e.what();
      f.unavailable = message.substr(0, message.find('\n'));
    }
    facts.push_back(f);
  }
#endif
  return facts;
}

// Each headless GL path, what it gives or why not, and the atlas page limits.
void print_gl() {
  std::printf("OpenGL (pose atlas):\n");
  for (const GlPathFacts& f : gl_paths()) {
    if (!f.unavailable.empty()) {
      std::printf("  %-16s unavailable: %s\n", f.name, f.unavailable.c_str());
      continue;
    }
    const int size = f.max_render_size;
    std::printf("  %-16s %s\n", f.name, f.context.c_str());
    std::printf("  %-16s atlas pages up to %dx%d px: %d tiles of 80x60 per row, %d per page\n", "", size, size,
                size / 80, (size / 80) * (size / 60));
  }
}

void print_info(bool extensions) {
  std::printf("CPU: --backend cpu runs the reference filter on %d threads (cpu:N for N; reference: one)\n",
              hardware_threads());
  const auto devices = compute::list_devices();
  for (const compute::Backend& backend : compute::backends()) {
    std::vector<const compute::DeviceInfo*> mine;
    for (const auto& d : devices)
      if (d.backend == backend.name) mine.push_back(&d);
    std::printf("%s: %zu device%s\n", backend.title.c_str(), mine.size(), mine.size() == 1 ? "" : "s");
    if (mine.empty()) std::printf("  %s\n", backend.unavailable_reason().c_str());
    for (const auto* d : mine) print_device(*d, extensions);
  }
  print_gl();
}

// The same facts as one JSON document, for scripts.
void print_info_json() {
  nlohmann::ordered_json root;
  root["version"] = DEPTHTRACK_VERSION;
  root["cpu"] = {{"backend", "cpu"}, {"threads", hardware_threads()}};
  const auto devices = compute::list_devices();
  for (const compute::Backend& backend : compute::backends()) {
    nlohmann::ordered_json list = nlohmann::json::array();
    for (const auto& d : devices) {
      if (d.backend != backend.name) continue;
      const AtlasPath path = find_atlas_path(d);
      nlohmann::ordered_json j = io::device_facts_json(d);
      if (path.unavailable.empty()) {
        j["atlas_gl"] = path.context;
        j["atlas_handoff"] = path.handoff;
      } else {
        j["atlas_gl_unavailable"] = path.unavailable;
      }
      j["extensions"] = d.extensions;
      list.push_back(j);
    }
    nlohmann::ordered_json b;
    b["devices"] = list;
    if (list.empty()) b["unavailable"] = backend.unavailable_reason();
    root[backend.name] = b;
  }
  nlohmann::ordered_json gl = nlohmann::json::array();
  for (const GlPathFacts& f : gl_paths()) {
    nlohmann::ordered_json j;
    j["path"] = f.name;
    if (f.unavailable.empty()) {
      j["context"] = f.context;
      j["max_render_size"] = f.max_render_size;
    } else {
      j["unavailable"] = f.unavailable;
    }
    gl.push_back(j);
  }
  root["gl"] = gl;
  std::printf("%s\n", root.dump(2).c_str());
}
}  // namespace

void add_info_command(CLI::App& app) {
  auto extensions = std::make_shared<bool>(false), json = std::make_shared<bool>(false);
  CLI::App* c = app.add_subcommand(
      "info",
      "List the compute devices of every backend with the GL context and atlas hand-off each gets, and the "
      "headless GL paths");
  c->add_flag("--extensions", *extensions, "Also print every device's full extension list");
  c->add_flag("--json", *json, "Print the same facts (and every extension) as one JSON document");
  c->callback([extensions, json] { *json ? print_info_json() : print_info(*extensions); });
}

}  // namespace depthtrack::cli
