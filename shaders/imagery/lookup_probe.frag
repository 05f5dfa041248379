#version 450 core
// The imagery virtual texture's lookups laid flat on the screen (render/imagery/
// imagery_textures.hpp; the GPU test compares each pixel with the CPU twin of the lookup): the
// pixel centred at gl_FragCoord looks up the frame position gl_FragCoord.xy * uProbeUnitsPerPixel
// relative to the camera. Output: the premultiplied sRGB colour imageryColour() returns.
#include "common/imagery.glsl"

uniform float uProbeUnitsPerPixel;
out vec4 fragColour;

void main() {
  fragColour = imageryColour(gl_FragCoord.xy * uProbeUnitsPerPixel);
}
