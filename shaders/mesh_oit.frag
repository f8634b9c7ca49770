#version 450
#extension GL_GOOGLE_include_directive : require
#include "fragment.glsl"
// Translucent lit mesh into the OIT accumulation (location 0) and revealage (location 1).
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec3 v_bary;
layout(location = 0) out vec4 out_accum;
layout(location = 1) out float out_reveal;

void main() {
  vec3 c = shade(pc.color.rgb, v_world, v_normal, v_bary);
  float a = pc.color.a;
  float w = oit_weight(a);
  out_accum = vec4(c * a, a) * w;
  out_reveal = a;
}
