#version 450
#extension GL_GOOGLE_include_directive : require
#include "push.glsl"
// Flat-coloured geometry: plane fills (world space) and ribbons (clip space, identity transform).
layout(location = 0) in vec4 in_pos;
layout(location = 1) in vec4 in_color;
layout(location = 0) out vec4 v_color;

void main() {
  v_color = in_color;
  gl_Position = pc.transform * in_pos;
}
