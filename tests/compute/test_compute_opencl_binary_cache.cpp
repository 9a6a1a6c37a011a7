// The program binary cache on an OpenCL device (compute/opencl/cl_cached_build.hpp): a binary the
// driver refuses is rebuilt and replaced, an unwritable folder costs only the time, and
// DEPTHTRACK_PROGRAM_CACHE=off turns it off. A second Tracker on any device: test_program_binary_cache.cpp.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "binary_cache_support.hpp"
#include "compute/opencl/cl_cached_build.hpp"
#include "compute/program_binary_cache.hpp"
#include "device_support.hpp"
#include "support.hpp"

using namespace depthtrack;
namespace fs = std::filesystem;
using compute::ProgramBinaryCache;
using test::ScopedEnv, test::read_all, test::write_all, test::files_in;

namespace {

// These cases build OpenCL C through the OpenCL queue.
bool opencl_device_available() {
  if (test::device_selector().rfind("opencl", 0) != 0) {
    std::cout << "SKIPPED: an OpenCL case; the test device is " << test::device_selector() << "\n";
    return false;
  }
  return test::device_available();
}

const char* const kTinySource = "kernel void add_one(global int* x) { x[get_global_id(0)] += 1; }\n";

}  // namespace

TEST_CASE("a binary the driver refuses is rebuilt and replaced, and an unwritable folder or off cost only time",
          "[compute][cache][device]") {
  if (!opencl_device_available()) return;
  const auto dir = test::temp_dir("binary_cache_refused");
  const ScopedEnv on("DEPTHTRACK_PROGRAM_CACHE", nullptr);
  const ScopedEnv xdg("XDG_CACHE_HOME", dir.c_str());
  const auto queue = compute::open_device(test::device_selector());
  const std::vector<std::string> definitions{"DT_UNUSED=1"};
  const ProgramBinaryCache cache(dir / "depthtrack" / "programs");
  const std::string key =
      compute::opencl::binary_cache_key(queue->info(), compute::opencl::build_options(definitions), kTinySource);

  // An intact file whose binary is not one the driver takes: built from source, then stored over it.
  REQUIRE(cache.store(key, "not a program binary"));
  const auto rebuilt = queue->build("tiny", kTinySource, definitions);
  CHECK_FALSE(rebuilt->loaded_from_disk());
  CHECK_NOTHROW(rebuilt->kernel("add_one"));
  const auto stored = cache.load(key);
  REQUIRE(stored);
  CHECK(*stored != "not a program binary");
  const auto loaded = queue->build("tiny", kTinySource, definitions);
  CHECK(loaded->loaded_from_disk());
  // The loaded program runs: one added to each element.
  auto memory = queue->allocate(4 * sizeof(int));
  const int input[4] = {1, 2, 3, 4};
  queue->write(*memory, 0, input, sizeof(input));
  auto kernel = loaded->kernel("add_one");
  kernel->set_arg(0, *memory);
  queue->launch(*kernel, compute::NdRange::linear(4, 1));
  int output[4] = {};
  queue->read(*memory, 0, output, sizeof(output));
  CHECK(output[0] == 2);
  CHECK(output[3] == 5);

  {
    const ScopedEnv off("DEPTHTRACK_PROGRAM_CACHE", "off");
    const ScopedEnv elsewhere("XDG_CACHE_HOME", (dir / "off").c_str());
    CHECK_FALSE(queue->build("tiny", kTinySource, definitions)->loaded_from_disk());
    CHECK_FALSE(fs::exists(dir / "off"));  // nothing written
  }
  write_all(dir / "blocker", "a file");
  const ScopedEnv blocked("XDG_CACHE_HOME", (dir / "blocker").c_str());
  std::unique_ptr<compute::Program> unwritable;
  CHECK_NOTHROW(unwritable = queue->build("tiny", kTinySource, definitions));
  REQUIRE(unwritable);
  CHECK_FALSE(unwritable->loaded_from_disk());
  CHECK_NOTHROW(unwritable->kernel("add_one"));
}
