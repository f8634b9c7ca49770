// Vertex stage of the lit meshes; mesh.vert and mesh_wire.vert include it (WIREFRAME adds the
// barycentric output, which costs lavapipe setup work per triangle, so it is only there when
// used). Vertices: position, vertex normal (world space).
#include "push.glsl"

layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
#ifdef WIREFRAME
layout(location = 2) out vec3 v_bary;
#endif

void main() {
  v_world = in_pos;
  v_normal = in_normal;
#ifdef WIREFRAME
  // Wireframe meshes are uploaded with three vertices per face (index 3f + k = corner k).
  int k = gl_VertexIndex % 3;
  v_bary = vec3(k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0);
#endif
  gl_Position = pc.transform * vec4(in_pos, 1.0);
}
