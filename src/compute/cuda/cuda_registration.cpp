// The CUDA backend's entry in the registry (compute/backend.hpp): its selectors and how they pick a device.
#include <algorithm>
#include <regex>

#include "compute/backend.hpp"
#include "compute/cuda/cuda_backend.hpp"

namespace depthtrack::compute::cuda {

namespace {
std::string absence() {
  return "no CUDA device: " + unavailable_reason();
}

std::unique_ptr<Queue> open_selected(const std::string& argument) {
  if (!argument.empty() && !std::regex_match(argument, std::regex(R"(\d+)")))
    throw NoSuchDevice("expected cuda or cuda:<device number>");
  const auto all = devices();
  if (all.empty()) throw NoSuchDevice(absence());
  const std::string wanted = "cuda:" + (argument.empty() ? std::string("0") : argument);
  const bool listed = std::any_of(all.begin(), all.end(), [&](const DeviceInfo& d) { return d.selector == wanted; });
  if (!listed) throw NoSuchDevice("there is no CUDA device " + wanted);
  return open(static_cast<unsigned>(std::stoul(wanted.substr(5))));
}
}  // namespace

Backend backend() {
  return Backend{"cuda", "CUDA", "cuda (= cuda:0), cuda:<n>", devices, absence, open_selected};
}

}  // namespace depthtrack::compute::cuda
