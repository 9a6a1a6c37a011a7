#include "compute/cuda/cuda_source_text.hpp"

#include <algorithm>
#include <cstdio>
#include <regex>
#include <sstream>
#include <vector>

#include "compute/cuda/cuda_program.hpp"

namespace depthtrack::compute::cuda {

std::vector<std::string> kernel_names(const std::string& source) {
  // The prelude turns `__kernel` into extern "C" __global__, so these are also the symbol names. An
  // attribute macro may stand before `void` (DT_RESIDENCY).
  static const std::regex kernel(R"(__kernel\s+(?:[A-Z_][A-Z0-9_]*\s+)?void\s+([A-Za-z_]\w*)\s*\()");
  std::vector<std::string> names;
  for (std::sregex_iterator it(source.begin(), source.end(), kernel), end; it != end; ++it)
    names.push_back((*it)[1].str());
  return names;
}

int first_error_line(const std::string& log) {
  static const std::regex error_at(R"(\((\d+)\): (catastrophic )?error)");
  std::smatch match;
  return std::regex_search(log, match, error_at) ? std::stoi(match[1].str()) : 0;
}

}  // namespace depthtrack::compute::cuda
