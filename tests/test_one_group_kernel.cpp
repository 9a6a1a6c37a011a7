// The one-group kernels' width (src/filter/one_group_kernel.hpp): narrow for small clouds, as wide as
// the device allows for large ones, and never wider than the kernel itself may run.
#include <catch2/catch.hpp>

#include "compute/device_info.hpp"
#include "device_support.hpp"
#include "filter/one_group_kernel.hpp"

using namespace depthtrack;

TEST_CASE("one-group kernels widen with the cloud within the device's work-group limit", "[filter]") {
  compute::DeviceInfo device;
  device.max_work_group_size = 1024;  // NVIDIA, AMD
  CHECK(one_group_size(2000, device) == 128);
  CHECK(one_group_size(16383, device) == 128);
  CHECK(one_group_size(16384, device) == 1024);
  CHECK(one_group_size(1000000, device) == 1024);
  device.max_work_group_size = 4096;  // PoCL: still at most kWidestGroup
  CHECK(one_group_size(1000000, device) == 1024);
  device.max_work_group_size = 768;  // not a power of two: the largest one below
  CHECK(one_group_size(1000000, device) == 512);
  device.max_work_group_size = 256;  // some Intel GPUs
  CHECK(one_group_size(1000000, device) == 256);
  device.max_work_group_size = 64;  // never below the narrow group the kernels were written for
  CHECK(one_group_size(1000000, device) == 128);
  device.max_work_group_size = 0;  // unknown
  CHECK(one_group_size(1000000, device) == 1024);
}

TEST_CASE("a one-group kernel is built no wider than the kernel itself may run", "[device][kernels]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  compute::ProgramCache programs(*q);
  for (const char* name : {"summarize", "prefix_sum"}) {
    const std::string file = std::string(name) == "summarize" ? "summarize.cl" : "resample.cl";
    const OneGroupKernel built = build_one_group_kernel(programs, file, name, {"DT_OCCLUSION=0"}, kWidestGroup);
    INFO(name << ": group " << built.group << ", the kernel's limit " << built.kernel->max_group_size());
    CHECK((built.group & (built.group - 1)) == 0);  // a power of two, as the group sums need
    CHECK(built.group <= kWidestGroup);
    if (built.kernel->max_group_size() > 0) CHECK(built.group <= built.kernel->max_group_size());
  }
}
