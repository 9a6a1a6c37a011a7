// The sketch backend's registry entry and queue: what a backend folder defines (compute::<name>::backend()),
// with its prelude embedded by depthtrack_compute_backend (prelude_files()) and put before every program.
#include <depthtrack/error.hpp>
#include <map>
#include <string>
#include <vector>

#include "compute/kernel_sources.hpp"
#include "compute/queue.hpp"
#include "sketch_backend.hpp"

namespace depthtrack::compute::sketch {

const std::map<std::string, std::string>& prelude_files();  // dt_prelude_sketch.h, embedded by CMake

namespace {
DeviceInfo sketch_device() {
  DeviceInfo info;
  info.backend = "sketch";
  info.selector = "sketch:0";
  info.platform = "depthtrack tests";
  info.name = "sketch device (computes nothing)";
  info.compute_units = 1;
  return info;
}

class SketchQueue final : public Queue {
 public:
  const DeviceInfo& info() const override { return info_; }
  std::unique_ptr<DeviceMemory> allocate(size_t bytes) override {
    throw BackendError("sketch: cannot allocate " + std::to_string(bytes) + " bytes: the sketch has no memory");
  }
  void write(DeviceMemory&, size_t, const void*, size_t) override { nothing("write"); }
  void read(const DeviceMemory&, size_t, void*, size_t) override { nothing("read"); }
  void* map_for_overwrite(DeviceMemory&, size_t, size_t) override { nothing("map"); }
  void unmap(DeviceMemory&, void*) override { nothing("unmap"); }
  void copy(const DeviceMemory&, size_t, DeviceMemory&, size_t, size_t) override { nothing("copy"); }
  // A backend compiles its prelude and then the source; the sketch says what it would have compiled.
  std::unique_ptr<Program> build(const std::string& name, const std::string& source,
                                 const std::vector<std::string>&) override {
    const std::string text = program_prelude(prelude_files(), "dt_prelude_sketch.h") + source;
    throw BackendError("sketch: cannot build program '" + name + "' (" + std::to_string(text.size()) +
                       " bytes beginning \"" + text.substr(0, text.find('\n')) + "\"): the sketch compiles nothing");
  }
  EventPtr launch(Kernel& kernel, const NdRange&) override { nothing("launch '" + kernel.name() + "'"); }
  void finish() override {}

 private:
  [[noreturn]] static void nothing(const std::string& what) {
    throw BackendError("sketch: cannot " + what + ": the sketch has no memory");
  }
  DeviceInfo info_ = sketch_device();
};

std::unique_ptr<Queue> open(const std::string& argument) {
  if (!argument.empty() && argument != "0") throw NoSuchDevice("there is no sketch device " + argument);
  return std::make_unique<SketchQueue>();
}
}  // namespace

Backend backend() {
  return Backend{"sketch",
                 "Sketch",
                 "sketch (= sketch:0)",
                 [] { return std::vector<DeviceInfo>{sketch_device()}; },
                 [] { return std::string("the sketch backend always has its device"); },
                 open};
}

}  // namespace depthtrack::compute::sketch
