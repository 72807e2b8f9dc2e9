# Embeds every shaders/*.glsl file into a generated C++ source as a raw string literal.
# The generated file registers the sources with osgLoA::ShaderLibrary's embedded table.
function(osgloa_embed_shaders out_var)
    set(options)
    set(one_value OUTPUT)
    set(multi SOURCES)
    cmake_parse_arguments(ARG "${options}" "${one_value}" "${multi}" ${ARGN})
    add_custom_command(
        OUTPUT "${ARG_OUTPUT}"
        COMMAND ${CMAKE_COMMAND} -DOUTPUT=${ARG_OUTPUT} "-DSOURCES=${ARG_SOURCES}"
                -P "${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake"
        DEPENDS ${ARG_SOURCES} "${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake"
        COMMENT "Embedding ${CMAKE_CURRENT_LIST_DIR} GLSL sources"
        VERBATIM)
    set(${out_var} "${ARG_OUTPUT}" PARENT_SCOPE)
endfunction()
