// Fragment stage of the lit meshes, included by mesh_{opaque,oit}{,_wire}.frag.
// OIT: write the weighted accumulation (location 0) and revealage (location 1) instead of an
// opaque colour. WIREFRAME: overlay triangle edges.
#include "fragment.glsl"

layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
#ifdef WIREFRAME
layout(location = 2) in vec3 v_bary;
#endif
#ifdef OIT
layout(location = 0) out vec4 out_accum;
layout(location = 1) out float out_reveal;
#else
layout(location = 0) out vec4 out_color;
#endif

void main() {
  vec3 c = shade(pc.color.rgb, v_world, v_normal);
#ifdef WIREFRAME
  c = wire_overlay(pc.color.rgb, c, v_bary);
#endif
#ifdef OIT
  float a = pc.color.a;
  out_accum = vec4(c * a, a) * oit_weight(a);
  out_reveal = a;
#else
  out_color = vec4(c, 1.0);
#endif
}
