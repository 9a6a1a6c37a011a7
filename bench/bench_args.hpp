#pragma once
// Command-line parsing shared by the benchmarks: numbers are read strictly (the whole text must be a
// positive integer), --help prints the usage and exits 0, anything else wrong exits 2 with a reason.
#include <functional>
#include <string>
#include <vector>

namespace depthtrack::bench {

// Thrown for a bad command line; main prints it with the usage and exits 2.
struct UsageError {
  std::string message;
};

// "12" -> 12; UsageError naming the option for "", "12x", "-3", "0", "1e3" or a number beyond int.
int parse_positive(const std::string& text, const std::string& option);
// "5e-5" -> 5e-5; UsageError naming the option for "", "1x", "-1", "nan", "inf".
double parse_nonnegative_double(const std::string& text, const std::string& option);
// "80x60" -> {80, 60}, each side strict as above.
std::pair<int, int> parse_size(const std::string& text, const std::string& option);
// "200,2000" -> {200, 2000}.
std::vector<int> parse_positive_list(const std::string& text, const std::string& option);

// Walks argv: an option taking a value gets it from the next argument.
class ArgReader {
 public:
  ArgReader(int argc, char** argv) : argc_(argc), argv_(argv) {}
  // The next option name, or "" at the end.
  std::string next();
  // The value after the option just read; UsageError when there is none.
  std::string value();

 private:
  int argc_, index_ = 0;
  char** argv_;
  std::string option_;
};

class ArgReader;
// A benchmark's command line: `option(name, args)` takes each option but --help/-h (which prints
// `usage`) and throws UsageError for one it does not know; a UsageError is printed as
// "program: reason" and the usage. Returns -1 when main should go on, else its exit status (0, 2).
int parse_command_line(int argc, char** argv, const char* program, const char* usage,
                       const std::function<void(const std::string& name, ArgReader& args)>& option);

}  // namespace depthtrack::bench
