#pragma once
// Compiled kernel programs kept on disk between runs, so a process does not compile (or, on PoCL,
// even preprocess) a program it ran before: a run's start-up is then a file read per program.
// One file per key (the device, its driver, the build options and the whole source), named by the
// key's hash; the file repeats the key and a checksum, so a hash collision, a truncated or corrupt
// file or another version's entry reads as a miss (the caller builds and stores again). Every file
// error is a miss or a skipped store, never an error of the run: the cache only saves time.
#include <filesystem>
#include <optional>
#include <string>

namespace depthtrack::compute {

class ProgramBinaryCache {
 public:
  // The folder to use: DEPTHTRACK_PROGRAM_CACHE=off (or 0) turns the cache off; otherwise
  // $XDG_CACHE_HOME/depthtrack/programs, else $HOME/.cache/depthtrack/programs; none without either.
  static std::optional<ProgramBinaryCache> from_environment();

  explicit ProgramBinaryCache(std::filesystem::path folder) : folder_(std::move(folder)) {}

  // The binary stored under key; nullopt when there is none or the file does not check out.
  std::optional<std::string> load(const std::string& key) const;
  // Writes a temporary file and renames it over the entry (concurrent processes see the old entry or
  // the new one, never half of one); false when that failed (unwritable folder, full disk).
  bool store(const std::string& key, const std::string& binary) const;
  // Where key's entry lives (tests corrupt it).
  std::filesystem::path path_of(const std::string& key) const;
  const std::filesystem::path& folder() const { return folder_; }

 private:
  std::filesystem::path folder_;
};

}  // namespace depthtrack::compute
