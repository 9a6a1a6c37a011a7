// The OpenCL backend's entry in the registry (compute/backend.hpp): its selectors and how they pick a device.
#include <algorithm>
#include <cctype>
#include <regex>

#include "compute/backend.hpp"
#include "compute/opencl/opencl_backend.hpp"

namespace depthtrack::compute::opencl {

namespace {
const char* const kNoDevice = "no OpenCL platform offers a device (the ICD loader found none; see /etc/OpenCL/vendors)";

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// Words a user types for a platform that its name does not contain.
std::vector<std::string> platform_words(const std::string& word) {
  if (word == "pocl") return {"portable computing language", "pocl"};
  if (word == "amd") return {"amd", "advanced micro devices"};
  return {word};
}

std::unique_ptr<Queue> open_index(const DeviceInfo& device) {
  std::smatch indices;
  const std::string text = device.selector.substr(device.selector.find(':') + 1);
  std::regex_match(text, indices, std::regex(R"((\d+)\.(\d+))"));
  return open(static_cast<unsigned>(std::stoul(indices[1].str())), static_cast<unsigned>(std::stoul(indices[2].str())));
}

std::unique_ptr<Queue> open_selected(const std::string& argument) {
  const auto all = devices();
  if (all.empty()) throw NoSuchDevice(kNoDevice);
  if (argument.empty()) {
    // Prefer a GPU, then the most compute units; the first listed wins a tie.
    const auto best = std::min_element(all.begin(), all.end(), [](const DeviceInfo& a, const DeviceInfo& b) {
      if (a.is_gpu != b.is_gpu) return a.is_gpu;
      return a.compute_units > b.compute_units;
    });
    return open_index(*best);
  }
  if (std::regex_match(argument, std::regex(R"(\d+\.\d+)"))) {
    const auto listed =
        std::find_if(all.begin(), all.end(), [&](const DeviceInfo& d) { return d.selector == "opencl:" + argument; });
    if (listed == all.end()) throw NoSuchDevice("no OpenCL device has the indices " + argument);
    return open_index(*listed);
  }
  for (const auto& word : platform_words(lower(argument)))
    for (const auto& device : all)
      if (lower(device.platform).find(word) != std::string::npos ||
          lower(device.vendor).find(word) != std::string::npos)
        return open_index(device);
  throw NoSuchDevice("no OpenCL platform's name or vendor contains '" + argument + "'");
}
}  // namespace

Backend backend() {
  return Backend{"opencl",
                 "OpenCL",
                 "opencl (the best OpenCL device), opencl:<word> (a platform whose name or vendor contains the "
                 "word, e.g. opencl:pocl, opencl:nvidia), opencl:<platform>.<device>",
                 devices,
                 [] { return std::string(kNoDevice); },
                 open_selected};
}

}  // namespace depthtrack::compute::opencl
