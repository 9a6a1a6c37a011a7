#pragma once
// What `depthtrack eval` prints: a table row per case, the summary, the confidence's reliability table.
#include <depthtrack/estimate.hpp>
#include <string>
#include <vector>

#include "eval/case_scores.hpp"
#include "eval/covariance_coverage.hpp"

namespace depthtrack::cli {

enum class CaseKind { Perturbed, Box, Gap };

struct CaseRow {
  std::string object, name;
  CaseKind kind = CaseKind::Perturbed;
  CaseScores scores;
  double seconds = 0;       // wall time of the case's tracking
  std::string box_source;   // Box: "label" or "projected"
  StepTimings first_frame;  // Box: the first frame's timings (search_ms: the search for the object in the box)
};

class EvalTable {
 public:
  // object_width: the longest object name, for aligned columns.
  explicit EvalTable(size_t object_width);
  void print_header() const;
  // Prints the row at once (a long run shows each case as it ends) and keeps it for the summary.
  void print_row(const CaseRow& row);
  void print_summary() const;

 private:
  size_t width_;
  std::vector<CaseRow> rows_;
};

void print_reliability(const Reliability& r);

// The covariance's coverage per case: the share of frames whose error lies inside the reported 95 % region.
struct CoverageRow {
  std::string object, name;
  Coverage coverage;
};
void print_coverage(const std::vector<CoverageRow>& rows, size_t object_width);

}  // namespace depthtrack::cli
