#version 330 core
// One instance per pose: transforms the mesh into the camera frame, projects it with the pinhole
// intrinsics into its tile of the atlas page and clips it to the tile's edges. Image row v lands
// on window row tile_y0 + v (no vertical flip), so the page reads back row-major like an image.
layout(location = 0) in vec3 a_position;

// Particle states (cl/dt_state.h): 4 RGBA32F texels per pose; texel 0 = (tx, ty, tz, qw), texel 1 =
// (qx, qy, qz, ...): camera_from_object as translation and unit quaternion, written by the compute
// device (or the host) in the layout the filter keeps them.
uniform samplerBuffer u_poses;
uniform int u_first_pose;       // pose of instance 0 on this page
uniform int u_tiles_per_row;
uniform vec2 u_tile_size;       // tile width, height in pixels
uniform vec2 u_page_size;       // page width, height in pixels
uniform vec4 u_intrinsics;      // fx, fy, cx, cy
uniform vec2 u_depth_map;       // clip z = x * z + y: OpenGL's near/far mapping for camera z

flat out vec4 v_pose[3];  // for atlas.frag's exact depth
flat out vec2 v_tile0;
out float gl_ClipDistance[4];

void main() {
  int pose = u_first_pose + gl_InstanceID;
  vec4 t_qw = texelFetch(u_poses, 4 * pose), q_xyz = texelFetch(u_poses, 4 * pose + 1);
  vec4 q = normalize(vec4(t_qw.w, q_xyz.xyz));  // w, x, y, z; normalized like the host's Pose
  float w = q.x, x = q.y, y = q.z, z = q.w;
  // The rows of [R | t] (the rotation matrix of a unit quaternion, as Eigen forms it).
  v_pose[0] = vec4(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y), t_qw.x);
  v_pose[1] = vec4(2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x), t_qw.y);
  v_pose[2] = vec4(2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y), t_qw.z);
  vec4 p = vec4(a_position, 1.0);
  vec3 c = vec3(dot(v_pose[0], p), dot(v_pose[1], p), dot(v_pose[2], p));
  v_tile0 = vec2(gl_InstanceID % u_tiles_per_row, gl_InstanceID / u_tiles_per_row) * u_tile_size;
  // Window coordinates times z: pixel u's centre is at window x = tile_x0 + u + 0.5, u = fx x/z + cx.
  vec2 window_z = (v_tile0 + u_intrinsics.zw + 0.5) * c.z + u_intrinsics.xy * c.xy;
  gl_Position = vec4(2.0 * window_z / u_page_size - c.z, u_depth_map.x * c.z + u_depth_map.y, c.z);
  // Linear in clip space, so the clipper cuts exactly at the tile's pixel boundaries.
  vec2 low = window_z - v_tile0 * c.z, high = (v_tile0 + u_tile_size) * c.z - window_z;
  gl_ClipDistance[0] = low.x;
  gl_ClipDistance[1] = high.x;
  gl_ClipDistance[2] = low.y;
  gl_ClipDistance[3] = high.y;
}
