// depthtrack.Estimate: every field of the C++ Estimate, the pose as a 4x4 numpy array.
#include <pybind11/eigen.h>

#include <depthtrack/tracker.hpp>

#include "bindings.hpp"
#include "convert.hpp"

namespace depthtrack::python {

void bind_estimate(py::module_& m) {
  py::class_<StepTimings>(m, "StepTimings", "Milliseconds each step of the frame took")
      .def_readonly("propagate_ms", &StepTimings::propagate_ms)
      .def_readonly("render_ms", &StepTimings::render_ms)
      .def_readonly("render_on_device", &StepTimings::render_on_device,
                    "render_ms from a device event or GL timer query (True) or the host clock (False)")
      .def_readonly("handoff_ms", &StepTimings::handoff_ms)
      .def_readonly("weigh_ms", &StepTimings::weigh_ms)
      .def_readonly("resample_ms", &StepTimings::resample_ms)
      .def_readonly("refine_ms", &StepTimings::refine_ms)
      .def_readonly("search_ms", &StepTimings::search_ms)
      .def_readonly("search_scoring_ms", &StepTimings::search_scoring_ms)
      .def_readonly("search_box_ms", &StepTimings::search_box_ms)
      .def_readonly("search_fit_ms", &StepTimings::search_fit_ms)
      .def_readonly("confidence_ms", &StepTimings::confidence_ms)
      .def_readonly("upload_ms", &StepTimings::upload_ms)
      .def_readonly("enqueue_ms", &StepTimings::enqueue_ms)
      .def_readonly("wait_ms", &StepTimings::wait_ms)
      .def_readonly("total_ms", &StepTimings::total_ms);

  py::class_<PoseEvidence>(m, "PoseEvidence", "What the frame's depth says about a pose (docs/confidence.md)")
      .def_readonly("pixels", &PoseEvidence::pixels, "pixels the silhouette covers at the working resolution")
      .def_readonly("visible", &PoseEvidence::visible, "of the measured silhouette pixels: on the surface")
      .def_readonly("occluded", &PoseEvidence::occluded, "of the measured silhouette pixels: something in front")
      .def_readonly("contradicted", &PoseEvidence::contradicted,
                    "of the measured silhouette pixels: seen behind where the object would be")
      .def_readonly("missing", &PoseEvidence::missing, "of the silhouette pixels: no depth")
      .def_readonly("separated", &PoseEvidence::separated,
                    "of the outline not against nearer surfaces: the share seeing past the edge")
      .def_readonly("outline_nearer", &PoseEvidence::outline_nearer, "of the outline: seen in front of the edge")
      .def_readonly("visible_rms", &PoseEvidence::visible_rms, "rms of (y - y_hat) / sigma(y) over visible pixels")
      .def_readonly("plane_rms", &PoseEvidence::plane_rms,
                    "the same for the best plane through the visible pixels' depths");

  py::class_<Estimate>(m, "Estimate", "One frame's estimate")
      .def_property_readonly(
          "pose", [](const Estimate& e) { return pose_to_matrix(e.pose); },
          "4x4 camera-from-object matrix, metres; a symmetric mesh's turn about its axis held where the depth cannot "
          "tell it")
      .def_property_readonly(
          "translation", [](const Estimate& e) { return e.pose.translation; }, "metres, camera frame")
      .def_property_readonly(
          "quaternion",
          [](const Estimate& e) {
            const auto& q = e.pose.rotation;
            return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
          },
          "rotation as qw, qx, qy, qz")
      .def_readonly("linear_velocity", &Estimate::linear_velocity, "m/s, object's local frame")
      .def_readonly("angular_velocity", &Estimate::angular_velocity, "rad/s, object's local frame")
      .def_readonly("effective_sample_size", &Estimate::effective_sample_size, "1 / sum w^2 before resampling")
      .def_property_readonly(
          "ess", [](const Estimate& e) { return e.effective_sample_size; }, "effective_sample_size")
      .def_readonly("max_log_likelihood", &Estimate::max_log_likelihood)
      .def_readonly("mean_log_likelihood", &Estimate::mean_log_likelihood)
      .def_readonly("resampled", &Estimate::resampled)
      .def_readonly("covariance", &Estimate::covariance,
                    "6x6 covariance of the refined pose: centre position (m), rotation vector (rad), camera frame; "
                    "scaled by the depth residual so that its 95 % region holds the error on about 95 % of frames "
                    "(docs/covariance.md); inf on the diagonal (0 across) for an axis the depth cannot determine; NaN "
                    "with refinement off")
      .def_readonly("refine_iterations", &Estimate::refine_iterations, "refinement steps tried this frame")
      .def_readonly("timings", &Estimate::timings)
      .def_readonly("confidence", &Estimate::confidence,
                    "probability that the pose is within tolerance of the truth (ADD-S <= 10 mm and a tenth of the "
                    "diameter): calibrated from `evidence`, raised by the run of supported frames before it (at most "
                    "0.99) where this frame's own evidence supports the pose")
      .def_readonly("evidence", &Estimate::evidence, "what the frame's depth says about the pose (PoseEvidence)")
      .def_property_readonly(
          "status", [](const Estimate& e) { return std::string(to_string(e.status)); }, "tracking, lost or no-data")
      .def_readonly("recovered", &Estimate::recovered,
                    "this frame re-seeded the filter: a search while lost found it, or after a gap in time")
      .def_readonly("search_poses", &Estimate::search_poses, "poses this frame's global search scored")
      .def_readonly("particles", &Estimate::particles,
                    "particles this frame ran with (config.budget_ms: the count the budget chose)")
      .def("__repr__", [](const Estimate& e) {
        const auto& t = e.pose.translation;
        return "Estimate(status=" + std::string(to_string(e.status)) + ", translation=[" + std::to_string(t.x()) +
               ", " + std::to_string(t.y()) + ", " + std::to_string(t.z()) +
               "], confidence=" + std::to_string(e.confidence) + ")";
      });
}

}  // namespace depthtrack::python
