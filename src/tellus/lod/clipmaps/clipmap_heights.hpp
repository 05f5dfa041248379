#pragma once
// Heights of the clipmap levels and the CPU reference of what the GPU draws. GL-free.
//
// Each level's texel holds two heights (Losasso & Hoppe's z_f, z_c): the level's own sample and
// the coarser level's surface at the same point, interpolated along the coarser level's
// triangulation (SW-NE diagonals, as buildFootprints makes them), so that with the blend
// weight at 1 a vertex lies exactly on the coarser level's triangle.
#include <functional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "tellus/lod/clipmaps/clipmap_layout.hpp"

namespace tellus::clipmaps {

// Height (metres) of level `level`'s sample at level coordinates `sample` (any integers: the
// sampler clamps to its data).
using LevelSampler = std::function<float(int level, glm::ivec2 sample)>;

// A level coordinate halved with a floor (an arithmetic shift), also for negative coordinates:
// the coarser level's sample at or before it.
inline glm::ivec2 halfFloor(glm::ivec2 p) { return {p.x >> 1, p.y >> 1}; }

// The coarser level's (level + 1) surface at the vertex `vertex` of `level`: it reads the
// coarser samples halfFloor(vertex - 1) to halfFloor(vertex + 1).
float coarserSurfaceHeight(const LevelSampler& sampler, int level, glm::ivec2 vertex);

// The two heights of a texel: (own, coarser surface); the coarsest level has no coarser one and
// repeats its own.
glm::vec2 texelHeights(const LevelSampler& sampler, const ClipmapShape& shape, int level, glm::ivec2 vertex);

// Every triangle the levels draw for a viewer at `viewer` (full-resolution (col, row)) with the
// given origins, no culling, each vertex as (col, row, height) in full-resolution samples with
// its geomorphed height: the CPU reference the GPU renderer is compared against.
std::vector<glm::vec3> referenceMesh(const ClipmapShape& shape, const Footprints& footprints,
                                     const std::vector<glm::ivec2>& origins, glm::dvec2 viewer,
                                     const LevelSampler& sampler);

}  // namespace tellus::clipmaps
