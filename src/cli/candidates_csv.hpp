#pragma once
// --candidates-out: the poses a start without a pose chose among, one CSV row each.
#include <depthtrack/evaluation.hpp>
#include <depthtrack/search_candidates.hpp>
#include <filesystem>
#include <vector>

namespace depthtrack::cli {

// rank (1 = the search's best),score,confidence,tx,ty,tz and the quaternion in `order`. InputError when
// the file cannot be written.
void write_candidates_csv(const std::filesystem::path& path, const std::vector<SearchCandidate>& candidates,
                          QuaternionOrder order);

}  // namespace depthtrack::cli
