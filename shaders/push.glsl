#ifndef PS_PUSH_GLSL
#define PS_PUSH_GLSL
// Push constants shared by all planesketch shaders (included with GL_GOOGLE_include_directive).
//
// Push constants (128 bytes, the guaranteed minimum), same layout for every pipeline; see
// engine/offscreen_renderer.cpp (struct PushConstants).
layout(push_constant) uniform Push {
  mat4 transform;  // world -> Vulkan clip, or identity for clip-space vertices (ribbons)
  vec4 color;      // mesh colour, straight alpha
  vec4 eye;        // xyz camera position; w = 1 perspective, 0 orthographic
  vec4 forward;    // xyz unit view direction; w = depth unit for OIT weights (eye-target distance)
  vec4 params;     // x unused; y = near plane; z = far - near (orthographic depth)
} pc;
#endif
