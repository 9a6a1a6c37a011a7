// A compute backend that lives outside the library: host memory, no kernels. It shows what adding a backend
// takes (docs/architecture.md, "Adding a compute backend"): this folder and one CMake line
// (tests/CMakeLists.txt); registered (test_backend_registry.cpp), the registry lists it, selection opens it,
// and its errors list its devices.
#include "fake_backend.hpp"

#include <cstring>
#include <depthtrack/error.hpp>
#include <vector>

#include "compute/backend.hpp"
#include "compute/queue.hpp"

namespace depthtrack::test::fake {

namespace {
class HostMemory final : public compute::DeviceMemory {
 public:
  explicit HostMemory(size_t bytes) : bytes_(bytes) {}
  size_t bytes() const override { return bytes_.size(); }
  std::vector<unsigned char> bytes_;
};

HostMemory& host(compute::DeviceMemory& memory) {
  return static_cast<HostMemory&>(memory);
}
const HostMemory& host(const compute::DeviceMemory& memory) {
  return static_cast<const HostMemory&>(memory);
}

compute::DeviceInfo fake_device() {
  compute::DeviceInfo info;
  info.backend = "fake";
  info.selector = "fake:0";
  info.platform = "depthtrack test";
  info.vendor = "nobody";
  info.name = "fake host-memory device";
  info.version = "fake 1";
  info.global_memory = size_t{1} << 30;
  info.max_allocation = size_t{1} << 28;
  info.compute_units = 1;
  return info;
}

class FakeQueue final : public compute::Queue {
 public:
  const compute::DeviceInfo& info() const override { return info_; }
  std::unique_ptr<compute::DeviceMemory> allocate(size_t bytes) override {
    if (bytes > info_.max_allocation)
      throw BackendError("fake: " + std::to_string(bytes) + " bytes is over the 256 MiB the fake device allocates");
    return std::make_unique<HostMemory>(bytes);
  }
  void write(compute::DeviceMemory& memory, size_t offset, const void* source, size_t bytes) override {
    std::memcpy(host(memory).bytes_.data() + offset, source, bytes);
  }
  void read(const compute::DeviceMemory& memory, size_t offset, void* destination, size_t bytes) override {
    std::memcpy(destination, host(memory).bytes_.data() + offset, bytes);
  }
  void* map_for_overwrite(compute::DeviceMemory& memory, size_t offset, size_t) override {
    return host(memory).bytes_.data() + offset;
  }
  void unmap(compute::DeviceMemory&, void*) override {}
  void copy(const compute::DeviceMemory& source, size_t source_offset, compute::DeviceMemory& destination,
            size_t destination_offset, size_t bytes) override {
    std::memcpy(host(destination).bytes_.data() + destination_offset, host(source).bytes_.data() + source_offset,
                bytes);
  }
  std::unique_ptr<compute::Program> build(const std::string& name, const std::string&,
                                          const std::vector<std::string>&) override {
    throw BackendError("fake: cannot build program '" + name + "': this backend runs no kernels");
  }
  compute::EventPtr launch(compute::Kernel& kernel, const compute::NdRange&) override {
    throw BackendError("fake: cannot launch '" + kernel.name() + "'");
  }
  void finish() override {}

 private:
  compute::DeviceInfo info_ = fake_device();
};

std::unique_ptr<compute::Queue> open(const std::string& argument) {
  if (!argument.empty() && argument != "0") throw compute::NoSuchDevice("there is no fake device " + argument);
  return std::make_unique<FakeQueue>();
}

}  // namespace

compute::Backend backend() {
  return compute::Backend{"fake",
                          "Fake",
                          "fake (= fake:0)",
                          [] { return std::vector<compute::DeviceInfo>{fake_device()}; },
                          [] { return std::string("the fake backend always has its device"); },
                          open};
}

}  // namespace depthtrack::test::fake
