#version 450 core
// ROAM: the leaves of the triangle bintree, split and merged on the CPU, streamed each frame as
// (u, v, h, level) vertices in grid units (roam_renderer.cpp); placed like every CPU-built mesh.
#include "common/grid_vertex.glsl"
