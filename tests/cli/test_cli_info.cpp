// depthtrack info: every compute device with the GL context and the atlas hand-off it would get.
#include <catch2/catch.hpp>
#include <sstream>

#include "compute/queue.hpp"
#include "device_support.hpp"
#include "support.hpp"

using namespace depthtrack;

TEST_CASE("info names the GL context and the atlas hand-off of every compute device", "[cli]") {
  const auto dir = test::temp_dir("cli_info");
  const auto [status, output] = test::run_cli("info", dir / "info.txt");
  INFO(output);
  REQUIRE(status == 0);
  CHECK(output.find("OpenGL (pose atlas):") != std::string::npos);
  const auto devices = compute::list_devices();
  // Each device's block (its indented lines) holds a hand-off, or why GL is unavailable for it.
  for (const auto& d : devices) {
    const size_t at = output.find("  " + d.selector + "  ");
    REQUIRE(at != std::string::npos);
    std::string block, line;
    std::istringstream lines(output.substr(at));
    std::getline(lines, block);
    while (std::getline(lines, line) && line.rfind("    ", 0) == 0) block += "\n" + line;
    const bool handoff = block.find("atlas hand-off    ") != std::string::npos;
    const bool unavailable = block.find("atlas GL          unavailable: ") != std::string::npos;
    CHECK(handoff != unavailable);
    // A platform without cl_khr_gl_sharing gets the bridge through exported memory (NVIDIA) or the
    // staged copy, which says why (PoCL).
    if (handoff && d.backend == "opencl" && !d.gl_sharing)
      CHECK((block.find("atlas hand-off    GL-OpenCL bridge") != std::string::npos ||
             block.find("staged copy (the OpenCL platform lacks cl_khr_gl_sharing") != std::string::npos));
  }
}

TEST_CASE("with no OpenGL at all the GL renderer stops with the paths it tried", "[cli][render][errors]") {
  if (!test::device_available() || !test::gl_built()) return;
  const auto dir = test::temp_dir("cli_no_gl");
  // glvnd with no EGL vendor library: EGL offers nothing; DEPTHTRACK_GL keeps OSMesa out.
  for (const char* path : {"egl-device", "egl-surfaceless"}) {
    const auto [status, output] =
        test::run_cli("demo --frames 2 --backend " + test::device_selector() + " --renderer gl", dir / "log.txt",
                      "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json DEPTHTRACK_GL=" + std::string(path));
    INFO(output);
    CHECK(status == 1);
    CHECK(output.find("no headless OpenGL 3.3 core context could be created; tried:") != std::string::npos);
    CHECK(output.find(std::string(path) + ": ") != std::string::npos);
  }
}
