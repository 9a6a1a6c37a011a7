// Device selection: turns "opencl", "opencl:pocl", "opencl:0.1", "cuda:0" into an open Queue.
#include <algorithm>
#include <cctype>
#include <depthtrack/error.hpp>
#include <regex>

#include "compute/opencl/opencl_backend.hpp"
#include "compute/queue.hpp"
#ifdef DEPTHTRACK_WITH_CUDA
#include "compute/cuda/cuda_backend.hpp"
#endif

namespace depthtrack::compute {

namespace {
const char* const kGrammar =
    "selectors: opencl (the best OpenCL device), opencl:<word> (a platform whose name or vendor contains the "
    "word, e.g. opencl:pocl, opencl:nvidia), opencl:<platform>.<device>, cuda (= cuda:0), cuda:<n>";

const char* const kNoOpenclDevice =
    "no OpenCL platform offers a device (the ICD loader found none; see /etc/OpenCL/vendors)";

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::string cuda_absence() {
#ifdef DEPTHTRACK_WITH_CUDA
  return "no CUDA device: " + cuda::unavailable_reason();
#else
  return "the CUDA backend was not built (no CUDA toolkit at build time)";
#endif
}

std::string available_devices() {
  std::string text = "available devices:";
  bool any_opencl = false, any_cuda = false;
  for (const auto& device : list_devices()) {
    text += "\n  " + device.selector + "  " + device.name + " (" + device.platform + ")";
    any_opencl = any_opencl || device.backend == "opencl";
    any_cuda = any_cuda || device.backend == "cuda";
  }
  if (!any_opencl) text += "\n  opencl: none (" + std::string(kNoOpenclDevice) + ")";
  if (!any_cuda) text += "\n  cuda: none (" + cuda_absence() + ")";
  return text;
}

// The first line says why; the rest lists what would have worked (`depthtrack info` shows the first line).
[[noreturn]] void fail(const std::string& selector, const std::string& why) {
  throw InputError("cannot open compute device '" + selector + "': " + why + "\n" + available_devices() + "\n" +
                   kGrammar);
}

// Words a user types for a platform that its name does not contain.
std::vector<std::string> platform_words(const std::string& word) {
  if (word == "pocl") return {"portable computing language", "pocl"};
  if (word == "amd") return {"amd", "advanced micro devices"};
  return {word};
}

std::unique_ptr<Queue> open_opencl(const std::string& selector, const std::string& argument) {
  const auto devices = opencl::devices();
  if (devices.empty()) fail(selector, kNoOpenclDevice);
  std::smatch indices;
  if (argument.empty()) {
    // Prefer a GPU, then the most compute units; the first listed wins a tie.
    const auto best = std::min_element(devices.begin(), devices.end(), [](const DeviceInfo& a, const DeviceInfo& b) {
      if (a.is_gpu != b.is_gpu) return a.is_gpu;
      return a.compute_units > b.compute_units;
    });
    return open_device(best->selector);
  }
  if (std::regex_match(argument, indices, std::regex(R"((\d+)\.(\d+))"))) {
    const bool listed = std::any_of(devices.begin(), devices.end(),
                                    [&](const DeviceInfo& d) { return d.selector == "opencl:" + argument; });
    if (!listed) fail(selector, "no OpenCL device has the indices " + argument);
    return opencl::open(static_cast<unsigned>(std::stoul(indices[1].str())),
                        static_cast<unsigned>(std::stoul(indices[2].str())));
  }
  for (const auto& word : platform_words(lower(argument)))
    for (const auto& device : devices)
      if (lower(device.platform).find(word) != std::string::npos ||
          lower(device.vendor).find(word) != std::string::npos)
        return open_device(device.selector);
  fail(selector, "no OpenCL platform's name or vendor contains '" + argument + "'");
}

std::unique_ptr<Queue> open_cuda(const std::string& selector, const std::string& argument) {
  if (!argument.empty() && !std::regex_match(argument, std::regex(R"(\d+)")))
    fail(selector, "expected cuda or cuda:<device number>");
#ifdef DEPTHTRACK_WITH_CUDA
  const auto devices = cuda::devices();
  if (devices.empty()) fail(selector, cuda_absence());
  const std::string wanted = "cuda:" + (argument.empty() ? std::string("0") : argument);
  const bool listed =
      std::any_of(devices.begin(), devices.end(), [&](const DeviceInfo& d) { return d.selector == wanted; });
  if (!listed) fail(selector, "there is no CUDA device " + wanted);
  return cuda::open(static_cast<unsigned>(std::stoul(wanted.substr(5))));
#else
  fail(selector, cuda_absence());
#endif
}
}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> devices = opencl::devices();
#ifdef DEPTHTRACK_WITH_CUDA
  for (auto& device : cuda::devices()) devices.push_back(std::move(device));
#endif
  return devices;
}

std::unique_ptr<Queue> open_device(const std::string& selector) {
  const std::string text = trim(selector);
  const auto colon = text.find(':');
  const std::string backend = lower(text.substr(0, colon));
  const std::string argument = colon == std::string::npos ? "" : trim(text.substr(colon + 1));
  if (colon != std::string::npos && argument.empty()) fail(selector, "nothing follows the ':'");
  if (backend == "opencl") return open_opencl(selector, argument);
  if (backend == "cuda") return open_cuda(selector, argument);
  fail(selector,
       text.empty() ? "the selector is empty" : "unknown backend '" + backend + "' (there are opencl and cuda)");
}

}  // namespace depthtrack::compute
