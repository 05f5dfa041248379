#pragma once
// Tellus's public API, all of it: open a terrain (terrain.hpp), draw it with a renderer picked by
// name (terrain_view.hpp), export it as glTF (terrain_export.hpp); results and errors
// (result.hpp). These headers need only the C++20 standard library; link tellus::tellus (CMake)
// or `pkg-config --libs tellus`.
#include "tellus/result.hpp"
#include "tellus/terrain.hpp"
#include "tellus/terrain_export.hpp"
#include "tellus/terrain_view.hpp"
