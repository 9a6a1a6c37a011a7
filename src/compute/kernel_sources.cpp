#include "compute/kernel_sources.hpp"

#include <cstdlib>
#include <depthtrack/error.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace depthtrack::compute {

const std::map<std::string, std::string>& kernel_registry();  // generated at build time

namespace {
// DEPTHTRACK_KERNEL_DIR: a folder whose files replace the embedded ones of the same name, read when a
// program is built (kernels edited without rebuilding; variants of one kernel timed by one build).
std::optional<std::string> override_text(const std::string& file) {
  const char* dir = std::getenv("DEPTHTRACK_KERNEL_DIR");
  if (!dir || !*dir) return std::nullopt;
  const std::filesystem::path folder(dir);
  if (!std::filesystem::is_directory(folder))
    throw BackendError("DEPTHTRACK_KERNEL_DIR '" + folder.string() + "' is not a folder");
  const std::filesystem::path path = folder / file;
  if (!std::filesystem::exists(path)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw BackendError("cannot read kernel source '" + path.string() + "' (DEPTHTRACK_KERNEL_DIR)");
  return text.str();
}

void inline_includes(const std::string& file, std::set<std::string>& done, std::ostringstream& out) {
  if (!done.insert(file).second) return;
  std::optional<std::string> text = override_text(file);
  if (!text) {
    const auto& files = kernel_registry();
    const auto it = files.find(file);
    if (it == files.end()) throw BackendError("kernel source '" + file + "' is not embedded (cl/ has no such file)");
    text = it->second;
  }
  std::istringstream in(*text);
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
