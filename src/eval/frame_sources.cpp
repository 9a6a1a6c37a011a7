// The kinds of frame source open_frame_source knows: the built-in ones below, then those registered.
#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/frame_source.hpp>
#include <mutex>

#include "io/raw_depth_stream.hpp"

namespace depthtrack {

namespace {

std::unique_ptr<FrameSource> open_folder(const std::string& location, const FrameSourceOptions& options) {
  return sequence_source(load_sequence(location, options.object));
}

struct Kind {
  std::string name, description;
  FrameSourceOpener open;
};

// The built-in kinds. A new kind is its opener in a file of its own and one line here (or, outside the
// library, one register_frame_source call).
std::vector<Kind> built_in() {
  return {
      {"folder",
       "a sequence folder: depthtrack's own (sequence.json), YCB-Video, BOP or ViSP's simulated (Depth/, "
       "CameraPose/, Config/)",
       open_folder},
      {"raw", "the raw depth stream from a file, a named pipe or - (stdin)", io::open_raw_depth_stream},
  };
}

struct Registry {
  std::mutex mutex;
  std::vector<Kind> kinds = built_in();
};

Registry& registry() {
  static Registry r;
  return r;
}

// The name of "KIND:LOCATION" when it is a plausible kind name (lower-case letters, digits, '-', '_').
std::string kind_part(const std::string& spec) {
  const auto colon = spec.find(':');
  if (colon == std::string::npos || colon == 0) return "";
  const std::string kind = spec.substr(0, colon);
  const bool name_like = std::all_of(kind.begin(), kind.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
  });
  return name_like ? kind : "";
}

}  // namespace

void register_frame_source(const std::string& kind, const std::string& description, FrameSourceOpener opener) {
  if (kind.empty() || kind_part(kind + ":") != kind)
    throw InputError("frame source kind '" + kind + "' must be lower-case letters, digits, '-' or '_'");
  if (!opener) throw InputError("frame source kind '" + kind + "' has no opener");
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  for (const Kind& k : r.kinds)
    if (k.name == kind) throw InputError("frame source kind '" + kind + "' is registered already");
  r.kinds.push_back({kind, description, std::move(opener)});
}

std::vector<std::pair<std::string, std::string>> frame_source_kinds() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  std::vector<std::pair<std::string, std::string>> kinds;
  for (const Kind& k : r.kinds) kinds.emplace_back(k.name, k.description);
  return kinds;
}

std::unique_ptr<FrameSource> open_frame_source(const std::string& spec, const FrameSourceOptions& options) {
  if (spec.empty()) throw InputError("no frame source given: KIND:LOCATION (folder:DIR, raw:-) or a folder");
  const std::string kind = kind_part(spec);
  FrameSourceOpener open;
  std::string known;
  {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    for (const Kind& k : r.kinds) {
      known += (known.empty() ? "" : ", ") + k.name;
      if (k.name == kind) open = k.open;
    }
  }
  if (open) return open(spec.substr(kind.size() + 1), options);
  std::error_code error;
  // A folder whose name merely holds a ':' is still a folder.
  if (!kind.empty() && !std::filesystem::exists(spec, error))
    throw InputError("frame source '" + spec + "': unknown kind '" + kind + "' (known: " + known + ")");
  return open_folder(spec, options);
}

}  // namespace depthtrack
