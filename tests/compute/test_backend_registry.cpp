// The backend registry: the built-in backends are listed in build order, and a backend registered from
// outside the library (tests/fake_backend/) is listed, selected and reported like them.
#include <algorithm>
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>
#include <vector>

#include "../fake_backend/fake_backend.hpp"
#include "../sketch_backend/sketch_backend.hpp"
#include "compute/backend.hpp"
#include "compute/buffer.hpp"
#include "compute/queue.hpp"

using namespace depthtrack;

namespace {
std::vector<std::string> backend_names() {
  std::vector<std::string> names;
  for (const auto& backend : compute::backends()) names.push_back(backend.name);
  return names;
}
}  // namespace

TEST_CASE("the registry lists the built-in backends first, then the test's fake one while registered",
          "[compute][registry]") {
  // OpenCL and CUDA are listed whether or not this build has them (then saying why they cannot open).
  CHECK(backend_names() == std::vector<std::string>{"opencl", "cuda"});
  {
    const compute::BackendRegistration fake(test::fake::backend());
    CHECK(backend_names() == std::vector<std::string>{"opencl", "cuda", "fake"});
    for (const auto& backend : compute::backends()) {
      INFO(backend.name);
      CHECK(!backend.title.empty());
      CHECK(backend.grammar.rfind(backend.name, 0) == 0);  // the selectors begin with the backend's name
      if (backend.devices().empty()) CHECK(!backend.unavailable_reason().empty());
    }
  }
  CHECK(backend_names() == std::vector<std::string>{"opencl", "cuda"});
  CHECK_THROWS_WITH(compute::open_device("fake"), Catch::Contains("unknown backend 'fake'"));
}

TEST_CASE("a registered backend's device is listed and opens by its selector", "[compute][registry]") {
  const compute::BackendRegistration registration(test::fake::backend());
  const auto devices = compute::list_devices();
  const auto fake = std::find_if(devices.begin(), devices.end(), [](const auto& d) { return d.backend == "fake"; });
  REQUIRE(fake != devices.end());
  CHECK(fake->selector == "fake:0");
  for (const char* selector : {"fake", "fake:0", " FAKE : 0 "}) {
    INFO(selector);
    const auto queue = compute::open_device(selector);
    CHECK(queue->info().name == "fake host-memory device");
    // The queue works through the common Buffer: what goes up comes back.
    compute::Buffer<int> buffer(*queue, 3);
    buffer.upload(std::vector<int>{4, 5, 6});
    CHECK(buffer.download() == std::vector<int>{4, 5, 6});
  }
}

TEST_CASE("a registered backend's errors name the selector and list every backend's devices",
          "[compute][registry][errors]") {
  const compute::BackendRegistration registration(test::fake::backend());
  CHECK_THROWS_WITH(compute::open_device("fake:7"),
                    Catch::StartsWith("cannot open compute device 'fake:7': there is no fake device 7") &&
                        Catch::Contains("available devices:") && Catch::Contains("fake:0  fake host-memory device") &&
                        Catch::Contains("fake (= fake:0)"));
  CHECK_THROWS_WITH(compute::open_device("quantum"),
                    Catch::Contains("unknown backend 'quantum' (there are opencl and cuda and fake)"));
  CHECK_THROWS_AS(compute::register_backend(test::fake::backend()), InputError);  // the name is taken
}

TEST_CASE("the tracker reaches a registered backend through TrackerConfig::backend", "[compute][registry]") {
  // The filter factory asks the registry, so "fake" is a device backend; it fails where it builds kernels.
  const compute::BackendRegistration registration(test::fake::backend());
  TrackerConfig config;
  config.backend = "fake";
  config.particles = 10;
  CHECK_THROWS_WITH(Tracker(builtin_demo_mesh(), Camera::make(80, 60, 66, 66, 39.5, 29.5), config),
                    Catch::Contains("fake: cannot build program"));
}

TEST_CASE("the sketch backend, one folder and one CMake line, is listed, opened and rejected like the others",
          "[compute][registry]") {
  // tests/sketch_backend/ is built by depthtrack_add_backend, as src/compute/opencl/ is; registered here.
  const compute::BackendRegistration registration(compute::sketch::backend());
  CHECK(backend_names() == std::vector<std::string>{"opencl", "cuda", "sketch"});
  const auto devices = compute::list_devices();
  CHECK(std::count_if(devices.begin(), devices.end(), [](const auto& d) { return d.selector == "sketch:0"; }) == 1);
  const auto queue = compute::open_device("sketch:0");
  CHECK(queue->info().backend == "sketch");
  // Its program text begins with its own prelude (dt_prelude_sketch.h, embedded from its folder), then the source.
  CHECK_THROWS_WITH(
      queue->build("p", "__kernel void k() {}\n", {}),
      Catch::StartsWith("sketch: cannot build program 'p'") && Catch::Contains("beginning \"/* dt_prelude_sketch.h:"));
  CHECK_THROWS_AS(compute::Buffer<int>(*queue, 3), BackendError);
  CHECK_THROWS_WITH(compute::open_device("sketch:2"),
                    Catch::StartsWith("cannot open compute device 'sketch:2': there is no sketch device 2") &&
                        Catch::Contains("sketch (= sketch:0)"));
  // The tracker reaches it through the filter factory and stops where it builds kernels, saying so.
  TrackerConfig config;
  config.backend = "sketch";
  config.particles = 10;
  CHECK_THROWS_WITH(Tracker(builtin_demo_mesh(), Camera::make(80, 60, 66, 66, 39.5, 29.5), config),
                    Catch::Contains("sketch: cannot"));
}
