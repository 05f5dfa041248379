#pragma once
// The list of renderer families (renderer_list.cpp): the one place that names them all.
#include <vector>

#include "tellus/render/registry/renderer_registry.hpp"

namespace tellus {

std::vector<const RendererFamily*> listRendererFamilies();

}  // namespace tellus
