#include "compute/program_binary_cache.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <system_error>

#include "compute/environment_switch.hpp"

namespace depthtrack::compute {

namespace {
// Bumped when the file layout changes: entries of another layout then read as misses.
constexpr char kMagic[] = "depthtrack program binary 1\n";
constexpr size_t kMagicBytes = sizeof(kMagic) - 1;

uint64_t fnv1a(const std::string& text, uint64_t hash = 14695981039346656037ull) {
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

std::string hex(uint64_t value) {
  static const char digits[] = "0123456789abcdef";
  std::string text(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4) text[static_cast<size_t>(i)] = digits[value & 15];
  return text;
}

void put_u64(std::string& out, uint64_t value) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

// Reads a little-endian u64 at offset, advancing it; false past the end.
bool get_u64(const std::string& in, size_t& offset, uint64_t& value) {
  if (in.size() < 8 || offset > in.size() - 8) return false;
  value = 0;
  for (int i = 0; i < 8; ++i) value |= uint64_t(static_cast<unsigned char>(in[offset + i])) << (8 * i);
  offset += 8;
  return true;
}

}  // namespace

std::optional<ProgramBinaryCache> ProgramBinaryCache::from_environment() {
  if (turned_off_by_environment("DEPTHTRACK_PROGRAM_CACHE")) return std::nullopt;
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg) return ProgramBinaryCache(std::filesystem::path(xdg) / "depthtrack" / "programs");
  const char* home = std::getenv("HOME");
  if (home && *home) return ProgramBinaryCache(std::filesystem::path(home) / ".cache" / "depthtrack" / "programs");
  return std::nullopt;
}

std::filesystem::path ProgramBinaryCache::path_of(const std::string& key) const {
  // Two differently seeded hashes: a file name collision is then rare, and harmless (the key is compared).
  return folder_ / (hex(fnv1a(key)) + hex(fnv1a(key, 0x9e3779b97f4a7c15ull)) + ".bin");
}

std::optional<std::string> ProgramBinaryCache::load(const std::string& key) const {
  std::ifstream file(path_of(key), std::ios::binary);
  if (!file) return std::nullopt;
  const std::string in((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad() || in.compare(0, kMagicBytes, kMagic) != 0) return std::nullopt;
  size_t offset = kMagicBytes;
  uint64_t key_bytes = 0, binary_bytes = 0, checksum = 0;
  if (!get_u64(in, offset, key_bytes) || key_bytes > in.size() - offset) return std::nullopt;
  if (in.compare(offset, key_bytes, key) != 0 || key_bytes != key.size()) return std::nullopt;
  offset += key_bytes;
  if (!get_u64(in, offset, binary_bytes) || binary_bytes == 0 || binary_bytes > in.size() - offset) return std::nullopt;
  std::string binary = in.substr(offset, binary_bytes);
  offset += binary_bytes;
  if (!get_u64(in, offset, checksum) || offset != in.size() || checksum != fnv1a(binary)) return std::nullopt;
  return binary;
}

bool ProgramBinaryCache::store(const std::string& key, const std::string& binary) const {
  std::error_code error;
  std::filesystem::create_directories(folder_, error);
  if (error) return false;
  std::string out(kMagic, kMagicBytes);
  put_u64(out, key.size());
  out += key;
  put_u64(out, binary.size());
  out += binary;
  put_u64(out, fnv1a(binary));
  // A name of this process and call: two processes storing one entry at once each write their own file.
  static std::atomic<unsigned> counter{0};
  const auto target = path_of(key);
  std::string suffix = std::to_string(::getpid());
  suffix.append(1, '.').append(std::to_string(counter++)).append(".tmp");
  auto temporary = target;
  temporary += suffix;
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file.write(out.data(), static_cast<std::streamsize>(out.size()));
    file.flush();
    if (!file) {
      file.close();
      std::filesystem::remove(temporary, error);
      return false;
    }
  }
  std::filesystem::rename(temporary, target, error);
  if (!error) return true;
  std::filesystem::remove(temporary, error);
  return false;
}

}  // namespace depthtrack::compute
