#include <depthtrack/search_candidates.hpp>

#include "tracker/tracker_impl.hpp"

namespace depthtrack {

namespace {
// The library's way in to a public Tracker's state, which its header keeps to the library (protected).
struct TrackerAccess : Tracker {
  static const Impl& of(const Tracker& tracker) { return *(tracker.*(&TrackerAccess::impl_)); }
};
}  // namespace

std::vector<SearchCandidate> search_candidates(const Tracker& tracker) {
  return TrackerAccess::of(tracker).search_candidates_;
}

}  // namespace depthtrack
