// Fragment-stage helpers shared by the planesketch fragment shaders.
#include "push.glsl"

// View depth of the current fragment (distance along the view direction).
float view_depth() {
  if (pc.eye.w > 0.5) return 1.0 / gl_FragCoord.w;  // perspective: clip w == view depth
  return pc.params.y + gl_FragCoord.z * pc.params.z;
}

// Weighted blended order-independent transparency (McGuire and Bavoil 2013, JCGT 2(2),
// eq. 7): weight falls off with view depth so nearer surfaces dominate. The depth is rescaled
// so the camera target sits at 10 units, the middle of the range the equation was tuned for;
// the upper clamp is lowered from 3e3 to 3e2 to keep sums inside float16 range.
float oit_weight(float alpha) {
  float z = 10.0 * view_depth() / max(pc.forward.w, 1e-20);
  float a = z / 5.0, b = z / 200.0, b3 = b * b * b;
  float w = 10.0 / (1e-5 + a * a + b3 * b3);
  return alpha * clamp(w, 1e-2, 3e2);
}

// Headlight shading (Lambert + Blinn with the light at the eye, so H == V), two-sided.
vec3 shade(vec3 base, vec3 world, vec3 normal) {
  vec3 V = pc.eye.w > 0.5 ? normalize(pc.eye.xyz - world) : -pc.forward.xyz;
  vec3 N = dot(normal, normal) > 1e-12 ? normalize(normal) : V;
  if (dot(N, V) < 0.0) N = -N;
  float ndl = max(dot(N, V), 0.0);
  float n3 = ndl * ndl * ndl, n6 = n3 * n3, n12 = n6 * n6, n24 = n12 * n12;
  float spec = n24 * n24;  // ndl^48 by squaring (pow is exp2(log2) on CPU drivers)
  return base * (0.25 + 0.75 * ndl) + vec3(0.15 * spec);
}

// Wireframe overlay: darken within about 1.2 px of a triangle edge (barycentric coordinates).
vec3 wire_overlay(vec3 base, vec3 c, vec3 bary) {
  vec3 d = fwidth(bary);
  vec3 a = smoothstep(vec3(0.0), 1.2 * d, bary);
  float edge = min(min(a.x, a.y), a.z);
  return mix(base * 0.3, c, edge);
}
