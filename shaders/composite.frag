#version 450
// OIT composite (McGuire and Bavoil 2013): the weighted average translucent colour, covering
// 1 - revealage of the pixel, blended over the opaque colour (SRC_ALPHA, ONE_MINUS_SRC_ALPHA).
layout(input_attachment_index = 0, set = 0, binding = 0) uniform subpassInput accum_in;
layout(input_attachment_index = 1, set = 0, binding = 1) uniform subpassInput reveal_in;
layout(location = 0) out vec4 out_color;

void main() {
  float reveal = subpassLoad(reveal_in).r;
  if (reveal >= 1.0) discard;  // no translucent fragment here
  vec4 accum = subpassLoad(accum_in);
  vec3 average = accum.rgb / max(accum.a, 1e-5);
  out_color = vec4(clamp(average, 0.0, 1.0), clamp(1.0 - reveal, 0.0, 1.0));
}
