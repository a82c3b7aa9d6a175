// Colour maps for the viewports (included before channel.frag.glsl).

// TURBO from a 256 x 1 lookup texture that the editor fills with OpenCV's table, so depth looks exactly
// like `goris render --maps` (near = red, far = blue).
uniform sampler2D u_turbo;

vec3 turbo(float t) {
  // Sample at texel centres so that t = 0 and t = 1 give the first and last entries.
  return texture(u_turbo, vec2(clamp(t, 0.0, 1.0) * (255.0 / 256.0) + 0.5 / 256.0, 0.5)).rgb;
}

// Depth through TURBO on inverse depth between the frame's far and near percentiles; black when empty.
vec3 depth_colour(float depth, float inv_near, float inv_far) {
  if (depth <= 0.0) return vec3(0.0);
  float t = (1.0 / depth - inv_far) / max(inv_near - inv_far, 1e-12);
  return turbo(t);
}

// Camera-space unit normal (OpenCV axes) as n * 0.5 + 0.5; black where nothing was hit (zero vector).
vec3 normal_colour(vec3 n) {
  return dot(n, n) > 0.0 ? n * 0.5 + 0.5 : vec3(0.0);
}

vec3 grey(float v) { return vec3(clamp(v, 0.0, 1.0)); }

// Selection / mask overlay: blends a tint over the covered pixels.
vec3 tint_overlay(vec3 base, vec3 tint, float coverage) {
  return mix(base, tint, 0.55 * clamp(coverage, 0.0, 1.0));
}
