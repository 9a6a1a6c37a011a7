#include "cli/parse_values.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <depthtrack/error.hpp>
#include <limits>
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

uint64_t parse_seed(const std::string& text, const std::string& option) {
  // Digits only: stoull would take "-1" as 2^64 - 1, and a float such as 1e21 is no seed.
  const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  errno = 0;
  const unsigned long long value = digits ? std::strtoull(text.c_str(), nullptr, 10) : 0;
  if (!digits || errno == ERANGE)
    throw InputError(option + " '" + text + "' is not a whole number from 0 to " +
                     std::to_string(std::numeric_limits<uint64_t>::max()));
  return static_cast<uint64_t>(value);
}

}  // namespace depthtrack::cli
