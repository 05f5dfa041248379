#version 450 core
// Geometry image warping: the regular grid moved towards where the importance map asks for
// detail on the CPU (lod/giw/giw_warp.cpp), streamed as (u, v, h, level) vertices in grid units;
// placed like every CPU-built mesh.
#include "common/grid_vertex.glsl"
