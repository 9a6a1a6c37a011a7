#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <fstream>
#include <numbers>

namespace depthtrack {

void write_tracking_csv(const std::filesystem::path& path, const std::vector<TrackedFrame>& frames) {
  std::ofstream out(path);
  if (!out) throw InputError("cannot write '" + path.string() + "'");
  const bool truth = !frames.empty() && std::all_of(frames.begin(), frames.end(),
                                                    [](const TrackedFrame& f) { return f.ground_truth.has_value(); });
  out << "frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess" << (truth ? ",err_t_mm,err_r_deg" : "") << ",confidence,status\n";
  out.precision(9);
  for (const auto& f : frames) {
    const Pose& p = f.estimate.pose;
    out << f.name << "," << f.timestamp << "," << p.translation.x() << "," << p.translation.y() << ","
        << p.translation.z() << "," << p.rotation.w() << "," << p.rotation.x() << "," << p.rotation.y() << ","
        << p.rotation.z() << "," << f.estimate.effective_sample_size;
    if (truth) out << "," << f.translation_error * 1000.0 << "," << f.rotation_error * 180.0 / std::numbers::pi;
    out << "," << f.estimate.confidence << "," << to_string(f.estimate.status);
    out << "\n";
  }
  if (!out) throw InputError("failed writing '" + path.string() + "'");
}

}  // namespace depthtrack
