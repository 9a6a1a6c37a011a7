#pragma once
// A device trackers run on, opened once and shared: several Trackers on one Device use its one compute
// queue and compile each kernel program once between them. The host filters are Devices too.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace depthtrack {

namespace compute {
struct DeviceContext;  // the library's compute queue and program cache (src/compute/program_cache.hpp)
}

// One compute device as `depthtrack info` lists it.
struct DeviceDescription {
  std::string selector;  // opens exactly this device: "opencl:0.1", "cuda:0"
  std::string backend;   // "opencl", "cuda"
  std::string name;      // e.g. "NVIDIA H200", "cpu-haswell-AMD EPYC ..."
  std::string platform;  // e.g. "Portable Computing Language", "NVIDIA CUDA"
  bool is_gpu = false;
};

class Device {
 public:
  // Every compute device of every backend built in (none where no runtime is installed). The host
  // selectors "reference", "cpu" and "cpu:N" always open and are not listed.
  static std::vector<DeviceDescription> list();
  // What TrackerConfig::backend accepts: "reference" (sequential host filter), "cpu" / "cpu:N" (the
  // reference on a thread pool), or a compute selector ("opencl", "opencl:pocl", "cuda:0", ...).
  // InputError naming the selector and listing what is available otherwise.
  static std::shared_ptr<Device> open(const std::string& selector);

  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const std::string& selector() const { return selector_; }
  bool is_host() const { return !context_; }  // reference or cpu: no compute queue
  // The compute device's name, or "host" for reference and cpu.
  std::string name() const;
  // Kernel programs compiled on this device so far (0 on the host): each (file, definitions) once.
  size_t program_builds() const;

  // The library's side of it; nullptr for a host Device.
  const std::shared_ptr<compute::DeviceContext>& context() const { return context_; }

 private:
  Device(std::string selector, std::shared_ptr<compute::DeviceContext> context);
  std::string selector_;
  std::shared_ptr<compute::DeviceContext> context_;
};

}  // namespace depthtrack
