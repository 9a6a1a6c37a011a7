// Device selection: turns "opencl", "opencl:pocl", "opencl:0.1", "cuda:0" into an open Queue by asking the
// backend the selector's first word names (compute/backend.hpp); no backend is named here.
#include <algorithm>
#include <cctype>
#include <depthtrack/error.hpp>

#include "compute/backend.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute {

namespace {
std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::string grammar() {
  std::string text = "selectors:";
  for (const Backend& backend : backends()) text += (text.back() == ':' ? " " : ", ") + backend.grammar;
  return text;
}

std::string available_devices() {
  std::string text = "available devices:";
  for (const Backend& backend : backends()) {
    const auto devices = backend.devices();
    for (const auto& device : devices)
      text += "\n  " + device.selector + "  " + device.name + " (" + device.platform + ")";
    if (devices.empty()) text += "\n  " + backend.name + ": none (" + backend.unavailable_reason() + ")";
  }
  return text;
}

// The first line says why; the rest lists what would have worked (`depthtrack info` shows the first line).
[[noreturn]] void fail(const std::string& selector, const std::string& why) {
  throw InputError("cannot open compute device '" + selector + "': " + why + "\n" + available_devices() + "\n" +
                   grammar());
}

std::string backend_names() {
  std::string names;
  for (const Backend& backend : backends()) names += (names.empty() ? "" : " and ") + backend.name;
  return names;
}
}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> devices;
  for (const Backend& backend : backends())
    for (auto& device : backend.devices()) devices.push_back(std::move(device));
  return devices;
}

std::unique_ptr<Queue> open_device(const std::string& selector) {
  const std::string text = trim(selector);
  const auto colon = text.find(':');
  const std::string name = lower(trim(text.substr(0, colon)));
  const std::string argument = colon == std::string::npos ? "" : trim(text.substr(colon + 1));
  if (colon != std::string::npos && argument.empty()) fail(selector, "nothing follows the ':'");
  const Backend* backend = find_backend(name);
  if (!backend)
    fail(selector,
         text.empty() ? "the selector is empty" : "unknown backend '" + name + "' (there are " + backend_names() + ")");
  if (!backend->open) fail(selector, backend->unavailable_reason());
  try {
    return backend->open(argument);
  } catch (const NoSuchDevice& e) {
    fail(selector, e.what());
  }
}

}  // namespace depthtrack::compute
