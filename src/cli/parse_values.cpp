#include "cli/parse_values.hpp"

#include <cmath>
#include <depthtrack/error.hpp>
#include <sstream>
#include <stdexcept>

namespace depthtrack::cli {

std::pair<int, int> parse_resolution(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> extra) || w <= 0 || h <= 0)
    throw InputError("resolution '" + text + "' is not of the form WxH with positive integers (e.g. 80x60)");
  return {w, h};
}

std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& option) {
  std::istringstream in(text);
  std::vector<double> values;
  std::string token;
  while (in >> token) {
    try {
      size_t used = 0;
      values.push_back(std::stod(token, &used));
      if (used != token.size() || !std::isfinite(values.back())) throw std::invalid_argument(token);
    } catch (const std::exception&) {
      throw InputError(option + ": '" + token + "' is not a finite number");
    }
  }
  if (values.size() != n)
    throw InputError(option + " takes " + std::to_string(n) + " numbers, got " + std::to_string(values.size()) +
                     " in '" + text + "'");
  return values;
}

}  // namespace depthtrack::cli
