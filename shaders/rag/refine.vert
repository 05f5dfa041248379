#version 450 core
// RAG refinement pass: the vertices go to the geometry shader unchanged.
layout(location = 0) in vec3 aGrid;  // (u, v, h)
out vec3 vGrid;

void main() {
  vGrid = aGrid;
}
