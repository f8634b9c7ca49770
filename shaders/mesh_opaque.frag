#version 450
#extension GL_GOOGLE_include_directive : require
#include "fragment.glsl"
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec3 v_bary;
layout(location = 0) out vec4 out_color;

void main() { out_color = vec4(shade(pc.color.rgb, v_world, v_normal, v_bary), 1.0); }
