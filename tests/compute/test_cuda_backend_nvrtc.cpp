// NVRTC alone, no GPU and no driver: the kernels under cl/ compile as CUDA through dt_prelude.h,
// and a broken one reports NVRTC's log. Skips where NVRTC cannot be loaded.
#if defined(DEPTHTRACK_WITH_CUDA)
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <iostream>

#include "compute/cuda/cuda_program.hpp"
#include "compute/kernel_sources.hpp"

using namespace depthtrack;
namespace cuda = depthtrack::compute::cuda;

namespace {
bool nvrtc_available() {
  const std::string reason = cuda::nvrtc_unavailable_reason();
  if (reason.empty()) return true;
  std::cout << "SKIPPED: " << reason << "\n";
  return false;
}

const char* const kRandomKernel = R"(
__kernel void random_words(__global uint* out, ulong seed, uint frame) {
  const uint i = get_global_id(0);
  const dt_philox4 w = dt_random_words(seed, i, frame, DT_STREAM_MOTION, 0u);
  for (uint k = 0; k < 4u; ++k) out[4u * i + k] = w.v[k] + OFFSET;
}
)";
}  // namespace

TEST_CASE("NVRTC compiles Philox from cl/ to PTX without a device", "[cuda]") {
  if (!nvrtc_available()) return;
  const std::string source = compute::kernel_source("philox.h") + kRandomKernel;
  const std::string ptx = cuda::compile_to_ptx(source, {"OFFSET=0u"}, 90);
  CHECK(ptx.find(".entry random_words") != std::string::npos);  // extern "C": the name is not mangled
  CHECK(ptx.find(".target sm_90") != std::string::npos);
  // A definition the source needs is passed through (without it, OFFSET is undeclared).
  CHECK_THROWS_AS(cuda::compile_to_ptx(source, {}, 90), BackendError);
}

TEST_CASE("A CUDA compile error carries NVRTC's log and the failing lines", "[cuda]") {
  if (!nvrtc_available()) return;
  const std::string source = compute::kernel_source("dt_prelude.h") +
                             "__kernel void broken(__global float* x) {\n  x[0] = not_declared_here\n}\n";
  std::string message;
  try {
    cuda::compile_to_ptx(source, {"FLAVOUR=1"}, 80);
  } catch (const BackendError& e) {
    message = e.what();
  }
  INFO(message);
  CHECK(message.find("nvrtcCompileProgram failed") != std::string::npos);
  CHECK(message.find("NVRTC_ERROR_COMPILATION") != std::string::npos);
  CHECK(message.find("-DFLAVOUR=1") != std::string::npos);
  CHECK(message.find("error") != std::string::npos);  // from the log
  CHECK(message.find("\"not_declared_here\" is undefined") != std::string::npos);
  CHECK(message.find("| __kernel void broken") != std::string::npos);  // the numbered source
}

TEST_CASE("The filter's kernels compile as CUDA for every occlusion variant", "[cuda]") {
  if (!nvrtc_available()) return;
  for (const std::string file :
       {"propagate.cl", "weigh.cl", "summarize.cl", "resample.cl", "refine.cl", "refine_spread.cl", "initialize.cl"}) {
    for (const std::string occlusion : {"0", "1", "2"}) {
      CAPTURE(file, occlusion);
      const std::string ptx =
          cuda::compile_to_ptx(compute::kernel_source(file), {"DT_GROUP_SIZE=256", "DT_OCCLUSION=" + occlusion}, 90);
      CHECK(ptx.find(".entry") != std::string::npos);
    }
  }
  // Drawing inside weigh at 80x60: with and without the vertices kept in work-group memory, with and
  // without the whole-image state index, moving the particles first or not.
  for (const std::string points : {"0", "423"})
    for (const std::string whole : {"0", "1"}) {
      CAPTURE(points, whole);
      const std::string ptx = cuda::compile_to_ptx(
          compute::kernel_source("render_weigh.cl"),
          {"DT_GROUP_SIZE=128", "DT_OCCLUSION=0", "DT_TILE_PIXELS=4800", "DT_SHARED_POINTS=" + points,
           "DT_WHOLE_IMAGE_STATE=" + whole, "DT_PROPAGATE_INSIDE=" + whole},
          90);
      CHECK(ptx.find(".entry render_weigh") != std::string::npos);
      CHECK(ptx.find(".minnctapersm") == std::string::npos);  // no residency asked for
    }
  // DT_RESIDENT_GROUPS becomes __launch_bounds__: PTX's minimum groups a multiprocessor, and the group size.
  const std::string bounded = cuda::compile_to_ptx(
      compute::kernel_source("render_weigh.cl"),
      {"DT_GROUP_SIZE=128", "DT_OCCLUSION=0", "DT_TILE_PIXELS=4800", "DT_SHARED_POINTS=423", "DT_RESIDENT_GROUPS=8"},
      90);
  CHECK(bounded.find(".minnctapersm 8") != std::string::npos);
  CHECK(bounded.find(".maxntid 128, 1, 1") != std::string::npos);
  const std::string rasterize =
      cuda::compile_to_ptx(compute::kernel_source("rasterize.cl"), {"DT_GROUP_SIZE=128", "DT_RESIDENT_GROUPS=8"}, 90);
  CHECK(rasterize.find(".minnctapersm 8") != std::string::npos);
}

TEST_CASE("CUDA architecture choice falls back to the newest one NVRTC knows", "[cuda]") {
  const std::vector<int> supported = {75, 80, 86, 89, 90, 100, 120};
  CHECK(cuda::choose_arch(90, supported) == 90);
  CHECK(cuda::choose_arch(87, supported) == 86);    // unknown in-between: an older PTX the driver can JIT
  CHECK(cuda::choose_arch(130, supported) == 120);  // a GPU newer than NVRTC
  CHECK(cuda::choose_arch(61, supported) == -1);    // older than NVRTC supports
}

TEST_CASE("Kernel names are read from the source text", "[cuda]") {
  const auto names = cuda::kernel_names(
      "#define __kernel x\n__kernel void alpha(int a) {}\n__kernel  void beta (int b);\n"
      "__kernel DT_RESIDENCY void gamma(int c) {}");
  CHECK(names == std::vector<std::string>{"alpha", "beta", "gamma"});
}

#endif
