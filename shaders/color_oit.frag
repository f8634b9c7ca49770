#version 450
#extension GL_GOOGLE_include_directive : require
#include "fragment.glsl"
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 out_accum;
layout(location = 1) out float out_reveal;

void main() {
  float a = v_color.a;
  float w = oit_weight(a);
  out_accum = vec4(v_color.rgb * a, a) * w;
  out_reveal = a;
}
