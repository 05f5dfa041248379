#version 450 core
// BDAM: one vertex of a patch in the GPU patch cache. Patches sit in fixed-size slots of the
// vertex buffer (uSlotVertices each); gl_VertexID (with the draw's base vertex) tells the slot,
// whose record gives the patch's origin and level. Positions in grid units: x samples east of the
// western column, y samples north of the southern row; the height travels with the vertex.

uniform mat4 uClipFromRelative;  // camera-relative world -> clip
uniform vec3 uCameraGrid;        // the camera in (x, y, h) grid units
uniform vec3 uGridScale;         // metres per unit: spacing x, spacing y, exaggeration
uniform float uMapStride;        // grid samples per height-texture sample
uniform int uSlotVertices;       // vertices a cache slot holds
layout(binding = 0) uniform sampler2D uHeights;  // shading texture, R32F metres, row 0 north

struct Slot {
  uvec4 originLevel;  // origin x, origin y (samples), patch level, unused
};
layout(std430, binding = 0) readonly buffer Slots { Slot slots[]; };

layout(location = 0) in uvec2 aLocal;  // samples from the patch's origin
layout(location = 1) in float aHeight;  // metres

out vec2 vTexCoord;
out float vHeight;
out vec3 vRelativePosition;
flat out int vLevel;

void main() {
  Slot slot = slots[gl_VertexID / uSlotVertices];
  vec2 p = vec2(slot.originLevel.xy + aLocal);
  vLevel = int(slot.originLevel.z);
  vec2 size = vec2(textureSize(uHeights, 0));
  vec2 map = p / uMapStride;
  vTexCoord = vec2(map.x + 0.5, size.y - 0.5 - map.y) / size;
  vHeight = aHeight;
  vRelativePosition = (vec3(p, aHeight) - uCameraGrid) * uGridScale;
  gl_Position = uClipFromRelative * vec4(vRelativePosition, 1.0);
}
