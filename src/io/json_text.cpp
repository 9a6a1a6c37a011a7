#include "io/json_text.hpp"

#include <fstream>
#include <sstream>

namespace depthtrack::io {

std::string read_bounded_file(const std::filesystem::path& path, size_t max_bytes, const std::string& what) {
  const std::string name = what + " '" + path.string() + "'";
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw InputError("cannot open " + name + ": no such file");
  // A device such as /dev/zero or a pipe has no size to check and may never end.
  if (!std::filesystem::is_regular_file(status)) throw InputError(name + " is not a regular file");
  const auto size = std::filesystem::file_size(path, error);
  if (error) throw InputError("cannot read " + name + ": " + error.message());
  if (size > max_bytes)
    throw InputError(name + " holds " + std::to_string(size) + " bytes, more than the " +
                     std::to_string(max_bytes >> 20) + " MiB allowed");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + name);
  std::string text(static_cast<size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) throw InputError("cannot read " + name);
  return text;
}

}  // namespace depthtrack::io
