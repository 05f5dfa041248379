#version 450 core
// A full-screen triangle for the atmosphere behind the globe (sky.frag).
out vec2 vNdc;

void main() {
  vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  vNdc = corner;
  gl_Position = vec4(corner, 0.0, 1.0);  // reversed-Z: 0 is the far plane
}
