#pragma once
// The backend registry: every compute backend (a folder under src/compute/) describes itself here, and
// device selection, `depthtrack info`, the filter factory and the GL hand-offs iterate the list instead of
// naming backends. The backends built into the library are listed by CMake (depthtrack_compute_backend in
// src/CMakeLists.txt generates the list); a program may add its own with register_backend.
#include <depthtrack/error.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "compute/device_info.hpp"

namespace depthtrack::compute {

class Queue;

// Thrown by Backend::open when its argument names no device; select_device adds the device list.
class NoSuchDevice : public InputError {
 public:
  using InputError::InputError;
};

struct Backend {
  std::string name;     // the selector's first word, and DeviceInfo::backend: "opencl", "cuda"
  std::string title;    // for people: "OpenCL", "CUDA"
  std::string grammar;  // the selectors it accepts, for messages: "cuda (= cuda:0), cuda:<n>"
  // Every device; empty (not an error) where the runtime is absent.
  std::function<std::vector<DeviceInfo>()> devices;
  // Why devices() is empty: no driver, not built.
  std::function<std::string()> unavailable_reason;
  // Opens the device `argument` names (the text after "name:", trimmed; empty for the bare name).
  // Throws NoSuchDevice saying why when it names none. Absent for a backend that was not built.
  std::function<std::unique_ptr<Queue>(const std::string& argument)> open;
};

// The built-in backends (in CMake's order), then those registered at run time.
const std::vector<Backend>& backends();
// Adds a backend; InputError when one of that name exists already. unregister_backend removes one
// registered at run time (the built-in ones stay).
void register_backend(Backend backend);
void unregister_backend(const std::string& name);
// The backend a selector's first word names, or nullptr.
const Backend* find_backend(const std::string& name);

// A backend from outside the library (a test's fake one, a plug-in) listed for this object's lifetime.
class BackendRegistration {
 public:
  explicit BackendRegistration(Backend backend) : name_(backend.name) { register_backend(std::move(backend)); }
  ~BackendRegistration() { unregister_backend(name_); }
  BackendRegistration(const BackendRegistration&) = delete;
  BackendRegistration& operator=(const BackendRegistration&) = delete;

 private:
  std::string name_;
};

}  // namespace depthtrack::compute
