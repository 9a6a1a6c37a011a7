#include "compute/kernel_sources.hpp"

#include <depthtrack/error.hpp>
#include <map>
#include <set>
#include <sstream>

namespace depthtrack::compute {

const std::map<std::string, std::string>& kernel_registry();  // generated at build time

namespace {
void inline_includes(const std::string& file, std::set<std::string>& done, std::ostringstream& out) {
  if (!done.insert(file).second) return;
  const auto& files = kernel_registry();
  const auto it = files.find(file);
  if (it == files.end()) throw BackendError("kernel source '" + file + "' is not embedded (cl/ has no such file)");
  std::istringstream in(it->second);
  for (std::string line; std::getline(in, line);) {
    const auto quote = line.find('"');
    if (line.rfind("#include \"", 0) == 0 && quote != std::string::npos) {
      inline_includes(line.substr(quote + 1, line.rfind('"') - quote - 1), done, out);
      continue;
    }
    out << line << '\n';
  }
}
}  // namespace

std::string kernel_source(const std::string& file) {
  std::set<std::string> done;
  std::ostringstream out;
  inline_includes(file, done, out);
  return out.str();
}

std::string program_prelude(const std::map<std::string, std::string>& embedded, const std::string& file) {
  const auto it = embedded.find(file);
  if (it == embedded.end()) throw BackendError("backend prelude '" + file + "' is not embedded");
  return it->second + (it->second.empty() || it->second.back() == '\n' ? "" : "\n") + "#line 1\n";
}

}  // namespace depthtrack::compute
