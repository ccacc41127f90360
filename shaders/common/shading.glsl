// Simple lighting shared by the patch and triangle fragment shaders.
#ifndef OSD_CULL_SHADING_GLSL
#define OSD_CULL_SHADING_GLSL

// A distinct, stable color per index (PCG hash).
vec3 debugColor(uint index) {
  uint h = index * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return vec3(float(h & 255u), float((h >> 8u) & 255u), float((h >> 16u) & 255u)) / 255.0 * 0.7 + 0.3;
}

// Headlight with a little ambient; two-sided (back faces lit like front faces).
vec3 shade(vec3 base, vec3 position, vec3 normal, vec3 eye) {
  vec3 v = normalize(eye - position);
  float len = length(normal);
  float ndotv = len > 0.0 ? abs(dot(normal / len, v)) : 1.0;
  return base * (0.2 + 0.8 * ndotv);
}
#endif
