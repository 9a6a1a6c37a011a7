#include "compute/source_excerpt.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <vector>

namespace depthtrack::compute {

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

}  // namespace depthtrack::compute
