// depthtrack info: every compute device of every backend, and what it offers depthtrack.
#include <cstdio>
#include <depthtrack/camera.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "compute/format_bytes.hpp"
#include "compute/queue.hpp"
#include "interop/atlas_handoff.hpp"
#include "render/atlas_renderer.hpp"
#include "render/gl_context.hpp"

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
// found by setting both up for a one-tile atlas, so what is printed is what happens.
void print_atlas_path(const compute::DeviceInfo& d) {
  try {
    auto queue = compute::open_device(d.selector);
    render::GlContextOptions options;
    options.device_uuid = d.uuid;
    render::GlContext context(options);
    render::AtlasRenderer renderer(context, builtin_demo_mesh(), Camera::make(80, 60, 66, 66, 39.5, 29.5), 0.05, 6);
    renderer.reserve(1);
    const auto handoff = interop::make_atlas_handoff(*queue, renderer);
    std::printf("    %-18s%s\n", "atlas GL", context.describe().c_str());
    std::printf("    %-18s%s\n", "atlas hand-off", handoff->name().c_str());
  } catch (const Error& e) {
    const std::string message = e.what();
    std::printf("    %-18sunavailable: %s\n", "atlas GL", message.substr(0, message.find('\n')).c_str());
  }
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
  print_atlas_path(d);
  if (extensions) print_extensions(d.extensions);
}

// Why a backend lists no device: opening it fails with the reason on the message's first line.
std::string absence_reason(const std::string& backend) {
  try {
    compute::open_device(backend);
  } catch (const Error& e) {
    const std::string message = e.what();
    const std::string first_line = message.substr(0, message.find('\n'));
    const auto reason = first_line.find("': ");  // after "cannot open compute device '<backend>'"
    return reason == std::string::npos ? first_line : first_line.substr(reason + 3);
  }
  return "it lists no device, yet one opened";
}

// Each headless GL path, what it gives or why not, and the atlas page limits.
void print_gl() {
  std::printf("OpenGL (pose atlas):\n");
  for (auto path : {render::GlPath::EglDevice, render::GlPath::EglSurfaceless, render::GlPath::OSMesa}) {
    try {
      render::GlContextOptions options;
      options.path = path;
      const render::GlContext context(options);
      std::printf("  %-16s %s\n", render::GlContext::path_name(path), context.describe().c_str());
      const int size = context.max_render_size();
      std::printf("  %-16s atlas pages up to %dx%d px: %d tiles of 80x60 per row, %d per page\n", "", size, size,
                  size / 80, (size / 80) * (size / 60));
    } catch (const Error& e) {
      const std::string message = e.what();
      std::printf("  %-16s unavailable: %s\n", render::GlContext::path_name(path),
                  message.substr(0, message.find('\n')).c_str());
    }
  }
}

void print_info(bool extensions) {
  const auto devices = compute::list_devices();
  const std::pair<const char*, const char*> backends[] = {{"opencl", "OpenCL"}, {"cuda", "CUDA"}};
  for (const auto& [backend, title] : backends) {
    std::vector<const compute::DeviceInfo*> mine;
    for (const auto& d : devices)
      if (d.backend == backend) mine.push_back(&d);
    std::printf("%s: %zu device%s\n", title, mine.size(), mine.size() == 1 ? "" : "s");
    if (mine.empty()) std::printf("  %s\n", absence_reason(backend).c_str());
    for (const auto* d : mine) print_device(*d, extensions);
  }
  print_gl();
}
}  // namespace

void add_info_command(CLI::App& app) {
  auto extensions = std::make_shared<bool>(false);
  CLI::App* c = app.add_subcommand(
      "info",
      "List the compute devices of every backend with the GL context and atlas hand-off each gets, and the "
      "headless GL paths");
  c->add_flag("--extensions", *extensions, "Also print every device's full extension list");
  c->callback([extensions] { print_info(*extensions); });
}

}  // namespace depthtrack::cli
