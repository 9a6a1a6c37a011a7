#include "bench_args.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "bench_rows.hpp"

namespace depthtrack::bench {

int parse_positive(const std::string& text, const std::string& option) {
  int value = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || stop != end || value <= 0)
    throw UsageError{option + ": '" + text + "' is not a positive integer"};
  return value;
}

double parse_nonnegative_double(const std::string& text, const std::string& option) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || stop != end || !std::isfinite(value) || value < 0)
    throw UsageError{option + ": '" + text + "' is not a number >= 0"};
  return value;
}

std::pair<int, int> parse_size(const std::string& text, const std::string& option) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw UsageError{option + ": '" + text + "' is not of the form WxH (e.g. 80x60)"};
  return {parse_positive(text.substr(0, x), option), parse_positive(text.substr(x + 1), option)};
}

std::vector<int> parse_positive_list(const std::string& text, const std::string& option) {
  std::vector<int> values;
  for (const std::string& part : split(text)) values.push_back(parse_positive(part, option));
  if (values.empty()) throw UsageError{option + ": no value given"};
  return values;
}

std::string ArgReader::next() {
  if (++index_ >= argc_) return "";
  option_ = argv_[index_];
  return option_;
}

std::string ArgReader::value() {
  if (index_ + 1 >= argc_) throw UsageError{option_ + " needs a value"};
  return argv_[++index_];
}

int parse_command_line(int argc, char** argv, const char* program, const char* usage,
                       const std::function<void(const std::string& name, ArgReader& args)>& option) {
  try {
    ArgReader args(argc, argv);
    for (std::string arg = args.next(); !arg.empty(); arg = args.next()) {
      if (arg == "--help" || arg == "-h") {
        std::printf("%s", usage);
        return 0;
      }
      option(arg, args);
    }
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\n%s", program, e.message.c_str(), usage);
    return 2;
  }
  return -1;
}

}  // namespace depthtrack::bench
