#include "cli/staged_outputs.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <depthtrack/error.hpp>

namespace depthtrack::cli {

namespace fs = std::filesystem;

namespace {

std::string quoted(const fs::path& path) {
  // Appended, not "'" + ... + "'": GCC 12 reports a false -Wrestrict on that form here.
  std::string text(1, '\'');
  text.append(path.native()).push_back('\'');
  return text;
}

// What names one file however it is spelt (relative, through a symbolic link, with "..").
fs::path key_of(const fs::path& path) {
  std::error_code error;
  const fs::path key = fs::weakly_canonical(fs::absolute(path), error);
  return error ? fs::absolute(path).lexically_normal() : key;
}

[[noreturn]] void refuse_input(const std::string& option, const fs::path& output, const fs::path& input) {
  throw InputError(option + " " + quoted(output) + " names an input of this run (" + quoted(input) +
                   "): writing it would destroy what it is computed from");
}

}  // namespace

StagedOutputs::~StagedOutputs() {
  if (committed_) return;
  std::error_code ignored;
  for (const Output& o : outputs_)
    if (o.partial != o.path) fs::remove(o.partial, ignored);
}

void StagedOutputs::add_input(const fs::path& path) {
  if (path.empty()) return;
  const fs::path key = key_of(path);
  if (const auto o = output_keys_.find(key); o != output_keys_.end())
    refuse_input(outputs_[o->second].option, outputs_[o->second].path, path);
  inputs_.emplace(key, path);
}

fs::path StagedOutputs::add(const std::string& option, const fs::path& path) {
  if (path.empty()) throw InputError(option + ": the output path is empty");
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (fs::is_directory(status)) throw InputError(option + " " + quoted(path) + " is a folder, not a file");
  Output output{option, path, path, {}};
  // A device or a pipe is written in place: there is nothing to replace.
  if (!fs::exists(status) || fs::is_regular_file(status)) {
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::is_directory(folder, error))
      throw InputError(option + " " + quoted(path) + ": the folder " + quoted(folder) + " does not exist");
    output.partial = path.string() + ".partial";
  }
  const fs::path key = key_of(path);
  if (const auto input = inputs_.find(key); input != inputs_.end()) refuse_input(option, path, input->second);
  if (const auto o = output_keys_.find(key); o != output_keys_.end() && output.partial != path)
    throw InputError(option + " " + quoted(path) + " is also the file of " + outputs_[o->second].option +
                     ": give each its own");
  output_keys_.emplace(key, outputs_.size());
  if (output.partial != path) output.listed = PartialFile(output.partial);
  outputs_.push_back(std::move(output));
  return outputs_.back().partial;
}

void StagedOutputs::commit() {
  // Earlier files moved aside, and the outputs already in place, to undo on a failed rename.
  std::vector<std::pair<fs::path, fs::path>> set_aside;
  std::vector<fs::path> placed;
  const auto undo = [&] {
    std::error_code ignored;
    for (const fs::path& path : placed) fs::remove(path, ignored);
    for (const auto& [path, previous] : set_aside) fs::rename(previous, path, ignored);
  };
  for (const Output& o : outputs_) {
    if (o.partial == o.path) continue;
    std::error_code error;
    if (fs::exists(o.path, error)) {
      const fs::path previous = o.path.string() + ".previous";
      fs::rename(o.path, previous, error);
      if (error) {
        undo();
        throw Error("cannot move the earlier " + quoted(o.path) + " aside: " + error.message());
      }
      set_aside.emplace_back(o.path, previous);
    }
    fs::rename(o.partial, o.path, error);
    if (error) {
      undo();
      throw Error("cannot rename " + quoted(o.partial) + " to " + quoted(o.path) + ": " + error.message());
    }
    placed.push_back(o.path);
  }
  std::error_code ignored;
  for (const auto& [path, previous] : set_aside) fs::remove(previous, ignored);
  for (Output& o : outputs_) o.listed.release();
  committed_ = true;
}

void write_text_file(const fs::path& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) throw Error("cannot write " + quoted(path) + ": " + std::strerror(errno));
  const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size() && std::fflush(file) == 0;
  const int code = errno;
  // Closed either way; a failed close (a full disk on a network file system) is a failed write too.
  if (std::fclose(file) != 0 || !written)
    throw Error("failed writing " + quoted(path) + ": " + std::strerror(written ? errno : code));
}

}  // namespace depthtrack::cli
