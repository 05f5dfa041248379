#version 450 core
// Draws the refined RAG mesh (the last pass's transform feedback buffer, or the coarse mesh).
#include "rag/rag_common.glsl"

layout(location = 0) in vec3 aGrid;  // (u, v, h)

out vec2 vTexCoord;          // into uHeights (row 0 north), for normals and the true height
out vec2 vGrid;              // (u, v), samples: where the reference's surface is read
out float vHeight;           // the drawn surface's height, metres
out vec3 vRelativePosition;  // camera-relative world position, metres

void main() {
  vec2 size = vec2(textureSize(uHeights, 0));
  vTexCoord = vec2(aGrid.x + 0.5, size.y - 0.5 - aGrid.y) / size;
  vGrid = aGrid.xy;
  vHeight = aGrid.z;
  vRelativePosition = (aGrid - uCameraGrid) * uGridScale;
  gl_Position = clipPosition(aGrid);
}
