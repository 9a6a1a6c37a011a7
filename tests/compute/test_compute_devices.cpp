// Device listing and selection.
#include <catch2/catch.hpp>
#include <iostream>
#include <set>

#include "compute_support.hpp"

using namespace depthtrack;

TEST_CASE("Listed devices have unique selectors that open them", "[compute]") {
  const auto devices = compute::list_devices();
  std::set<std::string> selectors;
  for (const auto& device : devices) {
    CAPTURE(device.selector);
    CHECK(selectors.insert(device.selector).second);
    CHECK((device.backend == "opencl" || device.backend == "cuda"));
    CHECK(device.selector.rfind(device.backend + ":", 0) == 0);
    CHECK(!device.name.empty());
    CHECK(device.max_allocation > 0);
    CHECK(device.max_allocation <= device.global_memory);
    auto queue = compute::open_device(device.selector);
    CHECK(queue->info().selector == device.selector);
    CHECK(queue->info().name == device.name);
  }
  if (devices.empty()) std::cout << "SKIPPED: no compute device is listed\n";
}

TEST_CASE("opencl:pocl opens PoCL's device where PoCL is installed", "[compute]") {
  for (const auto& device : compute::list_devices()) {
    if (device.platform != "Portable Computing Language") continue;
    CHECK(compute::open_device("opencl:pocl")->info().platform == "Portable Computing Language");
    CHECK(compute::open_device("OpenCL:PoCL ")->info().platform == "Portable Computing Language");
    return;
  }
  std::cout << "SKIPPED: no PoCL platform\n";
}

TEST_CASE("The plain backend selector opens the preferred device", "[compute]") {
  const auto devices = compute::list_devices();
  bool any_opencl = false, any_gpu = false;
  for (const auto& device : devices) {
    any_opencl = any_opencl || device.backend == "opencl";
    any_gpu = any_gpu || (device.backend == "opencl" && device.is_gpu);
  }
  if (!any_opencl) {
    CHECK_THROWS_AS(compute::open_device("opencl"), InputError);
    return;
  }
  const auto queue = compute::open_device("opencl");
  CHECK(queue->info().backend == "opencl");
  if (any_gpu) CHECK(queue->info().is_gpu);
}
