#version 450
#extension GL_GOOGLE_include_directive : require
#include "push.glsl"
// Lit meshes (opaque and translucent). Vertices: position, vertex normal (world space).
layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec3 v_bary;

void main() {
  v_world = in_pos;
  v_normal = in_normal;
  // Wireframe meshes are uploaded with three vertices per face (index 3f + k = corner k).
  int k = gl_VertexIndex % 3;
  v_bary = vec3(k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0);
  gl_Position = pc.transform * vec4(in_pos, 1.0);
}
