#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <fstream>
#include <numbers>

namespace depthtrack {

void write_tracking_csv(const std::filesystem::path& path, const std::vector<TrackedFrame>& frames,
                        QuaternionOrder order) {
  std::ofstream out(path);
  if (!out) throw InputError("cannot write '" + path.string() + "'");
  const bool truth = !frames.empty() && std::all_of(frames.begin(), frames.end(),
                                                    [](const TrackedFrame& f) { return f.ground_truth.has_value(); });
  const bool xyzw = order == QuaternionOrder::Xyzw;
  out << "frame,timestamp,tx,ty,tz," << (xyzw ? "qx,qy,qz,qw" : "qw,qx,qy,qz") << ",ess"
      << (truth ? ",err_t_mm,err_r_deg,adds_mm" : "") << ",latency_ms\n";
  out.precision(9);
  for (const auto& f : frames) {
    const Pose& p = f.estimate.pose;
    out << f.name << "," << f.timestamp << "," << p.translation.x() << "," << p.translation.y() << ","
        << p.translation.z() << ",";
    const Eigen::Quaterniond& q = p.rotation;
    if (xyzw)
      out << q.x() << "," << q.y() << "," << q.z() << "," << q.w();
    else
      out << q.w() << "," << q.x() << "," << q.y() << "," << q.z();
    out << "," << f.estimate.effective_sample_size;
    if (truth)
      out << "," << f.translation_error * 1000.0 << "," << f.rotation_error * 180.0 / std::numbers::pi << ","
          << f.adds * 1000.0;
    out << "," << f.latency_ms << "\n";
  }
  if (!out) throw InputError("failed writing '" + path.string() + "'");
}

}  // namespace depthtrack
