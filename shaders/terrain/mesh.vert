#version 450 core
// A terrain given as an explicit triangle mesh (CPU-built LOD meshes, test meshes): positions
// in metres relative to the mesh origin; the origin reaches the GPU camera-relative.

uniform mat4 uViewProjection;  // camera-relative world -> clip
uniform vec3 uMeshOrigin;      // mesh origin minus the camera position, metres
uniform float uExaggeration;   // vertical scale

layout(location = 0) in vec3 aPosition;  // metres from the mesh origin; z = height

out float vHeight;
out vec3 vRelativePosition;

void main() {
  vec3 position = uMeshOrigin + vec3(aPosition.xy, aPosition.z * uExaggeration);
  vHeight = aPosition.z;
  vRelativePosition = position;
  gl_Position = uViewProjection * vec4(position, 1.0);
}
