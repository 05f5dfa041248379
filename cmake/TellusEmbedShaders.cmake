# tellus_embed_shaders(TARGET target BASE_DIR dir FILES f1 f2 ...)
# Embeds GLSL files into a generated C++ source at build time. Each file becomes an entry
# of tellus::shaders::embeddedShaderSources(), keyed by its path relative to BASE_DIR
# (e.g. "terrain/reference.vert"). Editing a shader re-runs the generator.
set(_TELLUS_EMBED_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/embed_files.cmake")

function(tellus_embed_shaders)
  cmake_parse_arguments(ARG "" "TARGET;BASE_DIR" "FILES" ${ARGN})
  set(out "${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp")
  set(abs_files "")
  foreach(f IN LISTS ARG_FILES)
    list(APPEND abs_files "${ARG_BASE_DIR}/${f}")
  endforeach()
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${out} -DBASE_DIR=${ARG_BASE_DIR}
            "-DFILES=${ARG_FILES}" -P "${_TELLUS_EMBED_SCRIPT}"
    DEPENDS ${abs_files} "${_TELLUS_EMBED_SCRIPT}"
    COMMENT "Embedding ${ARG_TARGET} shaders"
    VERBATIM)
  target_sources(${ARG_TARGET} PRIVATE "${out}")
endfunction()
