// Shows one channel of the viewport's frame (textures: top row first, so v is flipped), with an optional
// label overlay, the selection tint and an optional comparison with the input photo.
in vec2 v_uv;
out vec4 o_colour;

uniform sampler2D u_source;  // the channel's texture
uniform int u_map;           // 0 rgb, 1 grey, 2 turbo on inverse depth, 3 normal as rgb
uniform int u_component;     // grey: which component of u_source (0..3)
uniform float u_gain;        // rgb and grey maps: values are multiplied by this first (exposure)
uniform float u_inv_near;    // depth range of the frame (inverse depths)
uniform float u_inv_far;

uniform int u_selection_on;    // 1: tint in proportion to the selected Gaussians' coverage
uniform sampler2D u_selection; // coverage in r (the frame's size)
uniform vec3 u_selection_tint;

uniform int u_overlay_on;            // 1: tint where u_overlay's component exceeds the threshold
uniform sampler2D u_overlay;
uniform int u_overlay_component;
uniform float u_overlay_threshold;
uniform vec3 u_tint;

uniform int u_photo_on;     // 1: pixels right of u_split show the photo
uniform sampler2D u_photo;
uniform float u_split;      // 0..1 across the image

float component(vec4 v, int c) {
  return c == 0 ? v.r : c == 1 ? v.g : c == 2 ? v.b : v.a;
}

void main() {
  vec2 uv = vec2(v_uv.x, 1.0 - v_uv.y);
  vec4 s = texture(u_source, uv);
  vec3 c;
  if (u_map == 1) c = grey(component(s, u_component) * u_gain);
  else if (u_map == 2) c = depth_colour(s.r, u_inv_near, u_inv_far);
  else if (u_map == 3) c = normal_colour(s.rgb);
  else c = clamp(s.rgb * u_gain, 0.0, 1.0);
  if (u_overlay_on == 1) {
    float m = component(texture(u_overlay, uv), u_overlay_component);
    c = tint_overlay(c, u_tint, m > u_overlay_threshold ? 1.0 : 0.0);
  }
  if (u_selection_on == 1) c = tint_overlay(c, u_selection_tint, texture(u_selection, uv).r);
  if (u_photo_on == 1 && v_uv.x > u_split) c = clamp(texture(u_photo, uv).rgb, 0.0, 1.0);
  if (u_photo_on == 1 && abs(v_uv.x - u_split) < fwidth(v_uv.x)) c = vec3(1.0);  // the slider's line
  o_colour = vec4(c, 1.0);
}
