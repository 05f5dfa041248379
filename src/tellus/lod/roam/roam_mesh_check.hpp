#pragma once
// Checks that a set of bintree leaves is a conforming triangulation of the bintree's domain:
// the leaves' areas add up to the domain's, and every edge is shared by exactly two leaves with
// the same two end points, unless it lies on the domain's outline (then by exactly one). A
// T-junction (a vertex inside a neighbour's edge: a crack) makes an edge that appears once
// away from the outline. GL-free; used by the tests after random split and merge sequences.
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/lod/roam/roam_error_bounds.hpp"

namespace tellus::roam {

Status checkConforming(const std::vector<BintreeTriangle>& leaves, const BintreeDomain& domain);

}  // namespace tellus::roam
