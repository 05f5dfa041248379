#version 450 core
// Wireframe overlay drawn over the shaded surface. Lines fade out where a grid cell projects
// to fewer than ~6 pixels, so distant terrain is not drowned in black.
uniform vec4 uWireColour;
uniform vec2 uSpacing;       // metres between samples
uniform float uPixelAngle;   // radians per pixel: 2 tan(fovY / 2) / image height
in vec3 vRelativePosition;
out vec4 fragColour;

void main() {
  float cellPixels = min(uSpacing.x, uSpacing.y) / (length(vRelativePosition) * uPixelAngle);
  fragColour = vec4(uWireColour.rgb, uWireColour.a * smoothstep(2.0, 6.0, cellPixels));
}
