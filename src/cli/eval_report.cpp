#include "cli/eval_report.hpp"

#include <algorithm>
#include <cstdio>

namespace depthtrack::cli {

namespace {

bool box_ended_within(const CaseRow& row) {
  return row.scores.last_adds <= kEndsWithin;
}

// The case's own check: false lost frames (perturbed), recovery (gap), where the box came from and
// whether the run ended within 10 mm (box).
std::string check(const CaseRow& row) {
  switch (row.kind) {
    case CaseKind::Perturbed:
      return "false_lost=" + std::to_string(row.scores.false_lost);
    case CaseKind::Gap:
      return std::string("recovered=") + (!row.scores.recovered ? "n/a" : *row.scores.recovered ? "yes" : "no");
    case CaseKind::Box: {
      const StepTimings& t = row.first_frame;
      char search[128];
      std::snprintf(search, sizeof search, " search_ms=%.0f (scoring %.0f, box %.0f, fits %.0f)", t.search_ms,
                    t.search_scoring_ms, t.search_box_ms, t.search_fit_ms);
      return "box=" + row.box_source + search + " ended_within_10mm=" + (box_ended_within(row) ? "yes" : "no");
    }
  }
  return "";
}

}  // namespace

EvalTable::EvalTable(size_t object_width) : width_(std::max<size_t>(object_width, 6)) {}

void EvalTable::print_header() const {
  std::printf("%-*s %-12s %6s %8s %6s %8s %8s %5s %7s %10s %8s  %s\n", static_cast<int>(width_), "object", "case",
              "frames", "adds_mm", "auc", "last_mm", "tracking", "lost", "no-data", "conf_wrong", "seconds", "check");
  std::fflush(stdout);
}

void EvalTable::print_row(const CaseRow& row) {
  const CaseScores& s = row.scores;
  std::printf("%-*s %-12s %6zu %8.2f %6.3f %8.2f %8zu %5zu %7zu %10zu %8.2f  %s\n", static_cast<int>(width_),
              row.object.c_str(), row.name.c_str(), s.frames, 1000 * s.mean_adds, s.auc, 1000 * s.last_adds, s.tracking,
              s.lost, s.no_data, s.confident_wrong, row.seconds, check(row).c_str());
  std::fflush(stdout);
  rows_.push_back(row);
}

void EvalTable::print_summary() const {
  size_t wrong = 0, boxes = 0, boxes_within = 0, gaps = 0, gaps_recovered = 0, false_lost = 0;
  double seconds = 0;
  for (const CaseRow& row : rows_) {
    wrong += row.scores.confident_wrong;
    seconds += row.seconds;
    if (row.kind == CaseKind::Perturbed) false_lost += row.scores.false_lost;
    if (row.kind == CaseKind::Box) {
      ++boxes;
      boxes_within += box_ended_within(row);
    }
    if (row.kind == CaseKind::Gap && row.scores.recovered) {
      ++gaps;
      gaps_recovered += *row.scores.recovered;
    }
  }
  std::printf(
      "summary: %zu cases in %.1f s; confident-wrong frames %zu; false lost frames (perturbed) %zu; box starts "
      "ending within 10 mm %zu of %zu; gap cases recovered within %zu frames %zu of %zu\n",
      rows_.size(), seconds, wrong, false_lost, boxes_within, boxes, kRecoveryFrames, gaps_recovered, gaps);
}

void print_reliability(const Reliability& r) {
  std::printf(
      "confidence reliability over %zu frames with ground truth (within tolerance: ADD-S <= min(10 mm, 10 %% "
      "of the diameter)):\n",
      r.frames);
  std::printf("%-9s %7s %15s %13s\n", "bin", "frames", "mean_confidence", "share_within");
  for (size_t b = 0; b < r.bins.size(); ++b) {
    const ReliabilityBin& bin = r.bins[b];
    char range[32];
    std::snprintf(range, sizeof range, "%.1f-%.1f", 0.1 * static_cast<double>(b), 0.1 * static_cast<double>(b + 1));
    if (bin.frames == 0)
      std::printf("%-9s %7zu %15s %13s\n", range, bin.frames, "-", "-");
    else
      std::printf("%-9s %7zu %15.3f %13.3f\n", range, bin.frames, bin.mean_confidence, bin.share_within);
  }
  std::printf("expected calibration error %.3f\n", r.ece);
}

void print_coverage(const std::vector<CoverageRow>& rows, size_t object_width) {
  std::printf(
      "covariance coverage (frames with ground truth and a covariance whose error, as a twist about the mesh's "
      "centre, lies inside the reported 95 %% region; undetermined axes left out; no_region: frames with ground truth "
      "whose covariance determined nothing (lost, barely supported or no fit), not in the share):\n");
  const int w = static_cast<int>(std::max<size_t>(object_width, 6));
  std::printf("%-*s %-12s %7s %7s %7s %15s %9s\n", w, "object", "case", "checked", "inside", "share", "wilson_95",
              "no_region");
  for (const CoverageRow& r : rows) {
    const Coverage& c = r.coverage;
    if (c.checked == 0) {
      std::printf("%-*s %-12s %7zu %7s %7s %15s %9zu\n", w, r.object.c_str(), r.name.c_str(), c.checked, "-", "-", "-",
                  c.no_region);
      continue;
    }
    char interval[32];
    std::snprintf(interval, sizeof interval, "%.3f-%.3f", c.low, c.high);
    std::printf("%-*s %-12s %7zu %7zu %7.3f %15s %9zu\n", w, r.object.c_str(), r.name.c_str(), c.checked, c.inside,
                c.share, interval, c.no_region);
  }
}

}  // namespace depthtrack::cli
