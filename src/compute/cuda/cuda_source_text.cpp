#include "compute/cuda/cuda_source_text.hpp"

#include <algorithm>
#include <cstdio>
#include <regex>
#include <sstream>
#include <vector>

#include "compute/cuda/cuda_program.hpp"

namespace depthtrack::compute::cuda {

std::vector<std::string> kernel_names(const std::string& source) {
  // The prelude turns `__kernel` into extern "C" __global__, so these are also the symbol names.
  static const std::regex kernel(R"(__kernel\s+void\s+([A-Za-z_]\w*)\s*\()");
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

std::string numbered_excerpt(const std::string& source, int line, int count) {
  std::vector<std::string> lines;
  std::istringstream in(source);
  for (std::string text; std::getline(in, text);) lines.push_back(text);
  const int total = static_cast<int>(lines.size());
  const int first = line > 0 ? std::max(1, std::min(line - count / 2, total - count + 1)) : 1;
  const int last = std::min(total, first + count - 1);
  std::ostringstream out;
  out << "source lines " << first << "-" << last << " of " << total << ":\n";
  for (int n = first; n <= last; ++n) {
    char number[16];
    std::snprintf(number, sizeof number, "%5d", n);
    out << (n == line ? '>' : ' ') << number << " | " << lines[static_cast<size_t>(n - 1)] << '\n';
  }
  return out.str();
}

}  // namespace depthtrack::compute::cuda
