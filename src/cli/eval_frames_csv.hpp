#pragma once
// `depthtrack eval --frames-out`: a row per frame of every case, for calibration plots and checks.
#include <depthtrack/evaluation.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/partial_files.hpp"
#include "eval/covariance_coverage.hpp"

namespace depthtrack::cli {

// object,case,frame,timestamp,adds_mm,confidence,status,within_tolerance,covariance_d2,covariance_dof,
// within_95,axis_d2_x,axis_d2_y,axis_d2_z,axis_d2_rx,axis_d2_ry,axis_d2_rz (adds_mm and within_tolerance
// empty where the frame has no ground truth; within_tolerance 1 or 0; the covariance's columns empty where
// the frame has no check: no ground truth or no covariance; an axis_d2 also where that axis is not
// determined: CovarianceCheck::axis_d2). As
// TrackingCsvWriter: the place is checked at construction, before any tracking; rows go to PATH.partial, which finish()
// renames to PATH; without finish() the partial file is removed and an earlier PATH stays.
class EvalFramesCsv {
 public:
  explicit EvalFramesCsv(const std::filesystem::path& path);
  ~EvalFramesCsv();
  EvalFramesCsv(const EvalFramesCsv&) = delete;
  EvalFramesCsv& operator=(const EvalFramesCsv&) = delete;

  void write(const std::string& object, const std::string& case_name, const TrackedFrame& frame, double tolerance,
             const std::optional<CovarianceCheck>& check);
  void finish();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_, partial_;
  std::ofstream out_;
  PartialFile listed_;  // removed if the run is interrupted
  bool finished_ = false;
};

}  // namespace depthtrack::cli
