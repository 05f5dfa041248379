# Precompiled headers. Parsing the standard library, glm, fmt and spdlog (and GoogleTest, CLI11
# and nlohmann/json where they are used) took a third to a half of each source file's compile
# time: about 680 headers for a file of the command. They are parsed once per group of targets
# that compile with the same flags instead of once per source file.
#
# tellus_precompile_headers(TARGET [HEADERS h...] [REUSE_FROM OTHER]): TARGET gets the common
# headers plus HEADERS, or reuses OTHER's precompiled header (OTHER must compile with the same
# options; definitions of macros the headers do not read may differ). The headers are only
# pre-parsed, never a dependency: every file still includes what it uses, and a build with
# -DTELLUS_PRECOMPILE_HEADERS=OFF checks that it does.
option(TELLUS_PRECOMPILE_HEADERS "Precompile the common third-party headers" ON)

set(TELLUS_COMMON_PRECOMPILED_HEADERS
  <algorithm> <array> <atomic> <chrono> <cmath> <cstddef> <cstdint> <cstring> <filesystem>
  <fstream> <functional> <limits> <map> <memory> <mutex> <optional> <set> <span> <string>
  <string_view> <unordered_map> <utility> <vector>
  <glm/glm.hpp> <fmt/format.h> <spdlog/spdlog.h>)

function(tellus_precompile_headers target)
  cmake_parse_arguments(PCH "" "REUSE_FROM" "HEADERS" ${ARGN})
  if(NOT TELLUS_PRECOMPILE_HEADERS)
    return()
  endif()
  # A precompiled header that cannot be used (other flags) is a warning, not a silent reparse.
  target_compile_options(${target} PRIVATE -Winvalid-pch)
  if(PCH_REUSE_FROM)
    target_precompile_headers(${target} REUSE_FROM ${PCH_REUSE_FROM})
  else()
    target_precompile_headers(${target} PRIVATE ${TELLUS_COMMON_PRECOMPILED_HEADERS} ${PCH_HEADERS})
  endif()
endfunction()

# The libraries (those of a TELLUS_TILES_ONLY build among them) share tellus_core's: they compile
# with the same options. Single-file libraries are left alone (nothing to share).
function(tellus_precompile_library_headers)
  tellus_precompile_headers(tellus_core)
  foreach(library IN ITEMS tellus_dem tellus_tiles tellus_tile_format tellus_stacks tellus_lod
                           tellus_gl tellus_render tellus_bdam tellus_eval tellus_export
                           tellus_api tellus_viewer)
    if(TARGET ${library})
      tellus_precompile_headers(${library} REUSE_FROM tellus_core)
    endif()
  endforeach()
endfunction()
