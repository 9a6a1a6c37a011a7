// Time of the GL pose atlas alone: one draw of N poses of the handset (or the built-in mesh), waited
// for with glFinish, for each depth-test variant, and GL's own time for it where GL has timer queries
// (gl_timer_draw_ms). Separates GL's share of a frame from the hand-off.
// Usage: depthtrack_bench_atlas [--particles N[,N...]] [--resolution WxH] [--repeats N]
#include <chrono>
#include <cstdio>
#include <depthtrack/mesh.hpp>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "atlas/gl/atlas_renderer.hpp"
#include "atlas/gl/gl_draw_timer.hpp"
#include "bench_args.hpp"
#include "bench_rows.hpp"

using namespace depthtrack;

namespace {
const char* const kUsage =
    "usage: depthtrack_bench_atlas [--particles N[,N...]] [--resolution WxH] [--repeats N]\n"
    "Times one GL draw of N poses of the handset (or the built-in mesh) with the exact and the early depth test;\n"
    "prints CSV rows backend,platform,device,driver,test,metric,unit,value.\n"
    "  --particles N[,N...]  poses per draw (default 2000,10000,100000)\n"
    "  --resolution WxH      tile size (default 80x60)\n"
    "  --repeats N           draws timed per case; the median is printed (default 5)\n";
}  // namespace

int main(int argc, char** argv) {
  std::vector<int> particle_counts = {2000, 10000, 100000};
  int width = 80, height = 60, repeats = 5;
  const auto option = [&](const std::string& arg, bench::ArgReader& args) {
    if (arg == "--particles")
      particle_counts = bench::parse_positive_list(args.value(), arg);
    else if (arg == "--resolution")
      std::tie(width, height) = bench::parse_size(args.value(), arg);
    else if (arg == "--repeats")
      repeats = bench::parse_positive(args.value(), arg);
    else
      throw bench::UsageError{"unknown option '" + arg + "'"};
  };
  if (const int status = bench::parse_command_line(argc, argv, "depthtrack_bench_atlas", kUsage, option); status >= 0)
    return status;
  try {
    std::string mesh_name;
    const Mesh mesh = bench::bench_mesh(mesh_name);
    const Camera camera =
        Camera::make(width, height, 0.82 * width, 0.82 * width, width / 2.0 - 0.5, height / 2.0 - 0.5);
    render::GlContext context;
    bench::print_header();
    for (const int count : particle_counts) {
      const std::string p = std::to_string(count);
      std::mt19937 rng(1);
      std::normal_distribution<double> gauss;
      std::vector<Pose> poses;
      for (int i = 0; i < count; ++i)
        poses.emplace_back(Eigen::Vector3d(0.02 * gauss(rng), 0.02 * gauss(rng), 0.6 + 0.02 * gauss(rng)),
                           Eigen::Quaterniond(1, 0.1 * gauss(rng), 0.1 * gauss(rng), 0.1 * gauss(rng)));
      for (const bool exact : {true, false}) {
        render::AtlasOptions options;
        options.exact_depth_test = exact;
        render::AtlasRenderer renderer(context, mesh, camera, 0.05, 6.0, options);
        renderer.render(poses);  // warm-up: allocation, shader compilation
        context.gl().Finish();
        render::GlDrawTimer timer(context);
        std::vector<double> ms, gl_ms;
        for (int r = 0; r < repeats; ++r) {
          const auto start = std::chrono::steady_clock::now();
          if (timer.available()) timer.begin();
          renderer.draw();
          const compute::EventPtr drawn = timer.available() ? timer.end() : nullptr;
          context.gl().Finish();
          ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
          if (drawn) gl_ms.push_back(drawn->elapsed_ms());
        }
        const std::string test = "atlas_" + mesh_name + "_" + std::to_string(width) + "x" + std::to_string(height) +
                                 "_" + p + "p_" + (exact ? "exact_depth_test" : "early_depth_test") + "_" +
                                 std::to_string(mesh.triangles.size()) + "tri";
        const double median = bench::median(ms);
        bench::print_row({"gl", "gl", context.describe(), "-", test, "draw_ms", "ms", median});
        // GL's own time for the draw (GL_TIME_ELAPSED), beside the host's wall time around it and a glFinish.
        if (!gl_ms.empty())
          bench::print_row({"gl", "gl", context.describe(), "-", test, "gl_timer_draw_ms", "ms", bench::median(gl_ms)});
        bench::print_row({"gl", "gl", context.describe(), "-", test, "triangles_per_second", "1/s",
                          1000.0 * static_cast<double>(count) * static_cast<double>(mesh.triangles.size()) / median});
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depthtrack_bench_atlas: %s\n", e.what());
    return 1;
  }
  return 0;
}
