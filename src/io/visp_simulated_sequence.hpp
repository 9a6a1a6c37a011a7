#pragma once
// ViSP's simulated depth sequences (the castle its model-based tracker's depth tutorials track), read as
// they are (load_sequence detects the folder) or converted into depthtrack's own layout:
//   Depth/Depth_NNNN.bin       uint32 height, uint32 width, then height * width uint16, all little-endian;
//                              metres = value * metres_per_unit, 0 = background (no measurement)
//   CameraPose/Camera_NNN.txt  the colour camera's pose cMo (4x4, metres), NNN the depth's frame number
//   Config/*_depth.xml         the depth camera's intrinsics (<px> <py> <u0> <v0>)
// The depth camera sits at depth_from_colour * cMo: the files do not say where, so the caller does.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/sequence.hpp>
#include <filesystem>

namespace depthtrack::io {

struct VispSimulatedImport {
  double metres_per_unit = 1.0 / 32768.0;  // ViSP's simulator: 0.000030518 m per unit
  Pose depth_from_colour;                  // the castle's: a translation of (-0.05, 0, 0)
  double rate = 30.0;                      // Hz: the files carry no timestamps
  // Where the simulator's renderer puts a pixel's centre, in the image coordinates of <u0> <v0>: 0.5,
  // the half-integer centres of a graphics renderer (the castle's u0 v0 of 320 240 is its 640x480
  // image's middle). depthtrack's pixel u sits at coordinate u, so the principal point moves by
  // -pixel_centre; the castle's ground truth, drawn so, meets its silhouettes (the test's share of
  // drawn pixels over background is lowest there).
  double pixel_centre = 0.5;
};

// One depth file, checked: its header against its size (before anything is allocated) and `expected`
// when given. Throws InputError naming the file.
DepthImage read_visp_depth(const std::filesystem::path& path, double metres_per_unit, int expected_width = 0,
                           int expected_height = 0);

// One pose file: four rows of four numbers, the last row 0 0 0 1, the 3x3 block a rotation.
Pose read_visp_pose(const std::filesystem::path& path);

// The intrinsics of a ViSP tracker configuration's <camera> block, for images of width x height.
Camera read_visp_camera(const std::filesystem::path& xml, int width, int height);

inline constexpr const char* kVispSimulatedFormat = "visp-simulated";

// The castle's: depth camera 5 cm along -x of the colour camera, 30 Hz, 1/32768 m per unit.
VispSimulatedImport castle_options();

// Whether dir holds the Depth/, CameraPose/ and Config/ folders of a ViSP simulated sequence.
bool is_visp_simulated_folder(const std::filesystem::path& dir);

// The folder `in` as a Sequence of format kVispSimulatedFormat whose frames name the Depth_NNNN.bin files
// (Sequence::load_depth reads them, checking each against the first frame's size). The poses and the
// intrinsics are read and checked here; InputError naming the file for a malformed or missing one.
Sequence load_visp_simulated_sequence(const std::filesystem::path& in, const VispSimulatedImport& options);

// Writes every frame of the folder `in` as a 16-bit PNG plus sequence.json into `out` (created). Every
// input file is checked before anything is written: a malformed one leaves `out` as it was. Returns
// the manifest written.
Sequence import_visp_simulated_sequence(const std::filesystem::path& in, const std::filesystem::path& out,
                                        const VispSimulatedImport& options);

}  // namespace depthtrack::io
