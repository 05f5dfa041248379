#pragma once
// Editing material stacks (beyond seed 003): a sphere of material added to, or removed from,
// the finest level, and the MipMap levels above it re-aggregated where the edit reaches.
// GL-free: `tellus stacks edit` and the viewer's brush both use it.
//
// Coordinates are the stack renderers' world frame: x east and y north of the south-west
// stack (stack column c at x = c * spacing, row r at y = (height - 1 - r) * spacing), z metres
// above the terrain's base.
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "tellus/core/result.hpp"
#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

struct SphereEdit {
  double xM = 0.0, yM = 0.0, zM = 0.0;  // centre
  double radiusM = 0.0;                 // > 0
  StackMaterial material = kAir;        // what fills the sphere; air removes
};

// A stroke a script applies before frame `frame` is drawn (tellus view --stack-edit, tellus
// bench --stack-edits).
struct ScriptedStackEdit {
  int frame = 0;
  SphereEdit edit;
};


// A column with [bottomM, topM) made `material` (air: emptied); valid if `column` is.
std::vector<StackLayer> fillInterval(std::span<const StackLayer> column, float bottomM,
                                     float topM, StackMaterial material);

// Checks the edit (finite, positive radius, within reach of the terrain; a removal may not dig
// under the base: z - r >= 0 is not required, heights below 0 are simply never solid).
Status checkSphereEdit(const StackTerrain& terrain, const SphereEdit& edit);

// Applies `edit` to every column whose centre lies in the sphere's disc: the column's
// interval inside the sphere becomes the material. Returns the columns changed.
Result<StackRegion> applySphereEdit(StackTerrain& terrain, const SphereEdit& edit);

// The first point along the ray from `origin` in the unit direction `direction` that lies in a
// solid layer of the column under it (the nearest stack), within `maxM` metres: the brush's
// target under the cursor. Marched at a quarter of the stack spacing, then refined.
std::optional<glm::dvec3> firstSolidAlongRay(const StackTerrain& terrain, const glm::dvec3& origin,
                                             const glm::dvec3& direction, double maxM);

// Re-aggregates, in every level above the finest, the stacks over `region` of level 0.
// Returns each level's region that changed (index 0: `region`).
std::vector<StackRegion> updatePyramid(std::vector<StackTerrain>& pyramid, StackRegion region);

}  // namespace tellus
