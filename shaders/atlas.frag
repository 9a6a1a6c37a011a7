#version 330 core
// Metric camera-frame z where the ray through the pixel centre meets the triangle's plane. Computed
// from the plane rather than interpolated, because the rasterizer snaps vertices to its sub-pixel
// grid (1/256 px on llvmpipe) and interpolated z then errs by up to slope x snap on grazing faces.
uniform samplerBuffer u_planes;  // per triangle: object-frame unit normal n and d, n . x = d
uniform vec4 u_intrinsics;       // fx, fy, cx, cy
uniform float u_inverse_far;

flat in vec4 v_pose[3];  // rows of [R | t]
flat in vec2 v_tile0;
layout(location = 0) out float o_depth;

void main() {
  vec4 plane = texelFetch(u_planes, gl_PrimitiveID);  // gl_PrimitiveID restarts with each instance
  vec3 n = vec3(dot(v_pose[0].xyz, plane.xyz), dot(v_pose[1].xyz, plane.xyz), dot(v_pose[2].xyz, plane.xyz));
  float d = plane.w + dot(n, vec3(v_pose[0].w, v_pose[1].w, v_pose[2].w));  // camera frame: n . x = d
  vec2 image = gl_FragCoord.xy - 0.5 - v_tile0;                            // exact pixel indices
  vec3 ray = vec3((image - u_intrinsics.zw) / u_intrinsics.xy, 1.0);
  float z = d / dot(n, ray);
  o_depth = z;
#ifdef DT_EXACT_DEPTH_TEST
  // The depth test compares this exact z too (linear in z, far -> 1, the clear value), so where two
  // surfaces nearly meet the nearer one wins as in the reference, not the one whose snapped,
  // interpolated depth happens to be smaller. Writing it turns off early depth rejection.
  gl_FragDepth = z * u_inverse_far;
#endif
}
