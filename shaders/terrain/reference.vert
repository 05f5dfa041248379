#version 450 core
// Brute-force reference renderer: one vertex per height sample, pulled from the chunk's
// height texture by gl_VertexID (no vertex attributes). The texture has a one-sample apron on
// every side, so texel (col + 1, row + 1) is vertex (col, row) of the chunk.

uniform mat4 uViewProjection;    // camera-relative world -> clip
uniform vec3 uChunkOrigin;       // world position of vertex (0, 0) minus the camera, metres
uniform vec2 uSpacing;           // metres between samples (x east-west, y north-south)
uniform int uChunkVertsX;        // vertices per chunk row
uniform float uExaggeration;     // vertical scale
layout(binding = 0) uniform sampler2D uHeights;

out vec2 vTexCoord;
out float vHeight;
out vec3 vRelativePosition;

void main() {
  int col = gl_VertexID % uChunkVertsX;
  int row = gl_VertexID / uChunkVertsX;
  float height = texelFetch(uHeights, ivec2(col + 1, row + 1), 0).r;
  vec3 position = uChunkOrigin + vec3(float(col) * uSpacing.x, -float(row) * uSpacing.y,
                                      height * uExaggeration);
  vTexCoord = (vec2(col, row) + 1.5) / vec2(textureSize(uHeights, 0));
  vHeight = height;
  vRelativePosition = position;
  gl_Position = uViewProjection * vec4(position, 1.0);
}
