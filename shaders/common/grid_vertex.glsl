// The vertex stage of a mesh the CPU streams in grid units (included by the vertex shaders of
// the renderers that build their meshes on the CPU: shaders/<algo>/<algo>.vert):
// (u, v, h, level) per vertex, u samples east of the western column, v north of the southern
// row, h metres, level the level-of-detail tint; shaded by common/height_texture_surface.frag.

uniform mat4 uClipFromRelative;  // camera-relative world -> clip
uniform vec3 uCameraGrid;        // the camera in (u, v, h) units
uniform vec3 uGridScale;         // metres per unit: spacing x, spacing y, exaggeration
uniform float uMapStride;        // grid samples per height-texture sample (1, or 2^level)
layout(binding = 0) uniform sampler2D uHeights;  // R32F metres, row 0 north (maybe a coarser level)

layout(location = 0) in vec4 aVertex;

out vec2 vTexCoord;          // into uHeights, for normals and the true height
out float vHeight;           // the drawn surface's height, metres
out vec3 vRelativePosition;  // camera-relative world position, metres
flat out int vLevel;         // the triangle's level of detail (lod shading)

void main() {
  vec3 aGrid = aVertex.xyz;
  vLevel = int(aVertex.w);
  // Map sample (i, j) is grid sample (i, j) * uMapStride, both counted from the south-west.
  vec2 size = vec2(textureSize(uHeights, 0));
  vec2 map = aGrid.xy / uMapStride;
  vTexCoord = vec2(map.x + 0.5, size.y - 0.5 - map.y) / size;
  vHeight = aGrid.z;
  vRelativePosition = (aGrid - uCameraGrid) * uGridScale;
  gl_Position = uClipFromRelative * vec4(vRelativePosition, 1.0);
}
