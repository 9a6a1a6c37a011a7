// Frame sources in Python: depthtrack.open_source(spec) is an iterator of Frames (depth as numpy), so that a
// script reads a folder, a raw stream on stdin or a named pipe as `depthtrack track --source` does.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <depthtrack/frame_source.hpp>
#include <optional>

#include "bindings.hpp"
#include "convert.hpp"

namespace depthtrack::python {

namespace {
// The depth as a (height, width) float32 array of metres, NaN where missing.
py::array_t<float> depth_array(const Frame& frame) {
  const DepthImage& depth = frame.depth;
  py::array_t<float> out({static_cast<py::ssize_t>(depth.height()), static_cast<py::ssize_t>(depth.width())});
  std::copy(depth.data().begin(), depth.data().end(), out.mutable_data());
  return out;
}

std::optional<py::array_t<double>> truth_matrix(const Frame& frame) {
  if (!frame.ground_truth) return std::nullopt;
  return pose_to_matrix(*frame.ground_truth);
}

Frame next_frame(FrameSource& source) {
  std::optional<Frame> frame;
  {
    const py::gil_scoped_release release;  // a stream may wait for its writer
    frame = source.next();
  }
  if (!frame) throw py::stop_iteration();
  return std::move(*frame);
}

std::unique_ptr<FrameSource> open_source(const std::string& spec, const std::string& object,
                                         const std::string& frames) {
  std::unique_ptr<FrameSource> source = open_frame_source(spec, FrameSourceOptions{object});
  if (!frames.empty()) source = frames_in(std::move(source), parse_frame_range(frames, "frames"));
  return source;
}
}  // namespace

void bind_frame_source(py::module_& m) {
  py::class_<Frame>(m, "Frame", "One frame of a frame source")
      .def_readonly("name", &Frame::name)
      .def_readonly("timestamp", &Frame::timestamp, "seconds")
      .def_property_readonly("depth", &depth_array, "(height, width) float32 metres, NaN = missing")
      .def_property_readonly("ground_truth", &truth_matrix,
                             "4x4 camera-from-object of the tracked object (metres), or None")
      .def_readonly("colour_path", &Frame::colour_path, "a registered colour image on disk, or an empty path");
  py::class_<FrameSource>(m, "FrameSource", "Frames from one camera, read once, in order (an iterator)")
      .def_property_readonly("camera", &FrameSource::camera)
      .def_property_readonly("size", &FrameSource::size, "frames it holds when known beforehand (a folder), else None")
      .def("__iter__", [](FrameSource& s) -> FrameSource& { return s; })
      .def("__next__", &next_frame);
  m.def("open_source", &open_source, py::arg("spec"), py::arg("object") = "", py::arg("frames") = "",
        "Frames from spec: a sequence folder, 'folder:DIR', or 'raw:PATH' / 'raw:-' (stdin) for the raw depth "
        "stream (depthtrack.RAW_STREAM_FORMAT); object picks a folder's ground truth, frames a range 'A:B'");
  m.attr("RAW_STREAM_FORMAT") = raw_stream_format();
}

}  // namespace depthtrack::python
