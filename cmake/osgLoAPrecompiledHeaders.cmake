# Precompiled headers (OSGLOA_PRECOMPILED_HEADERS, default ON): the build's time goes mostly into
# parsing the same OpenSceneGraph, GoogleTest and standard headers in every source file (GCC's
# -ftime-report on a test: 54 % parsing, 23 % deferred template work, 23 % code generation).
# One header set per family of targets, compiled once:
#   - libosgLoA: its own PCH;
#   - the serializer plugin (35 wrapper files, osgDB's serializer templates): its own PCH;
#   - the test programs: one PCH, made by the first test and reused by the others (REUSE_FROM);
#   - the tools: one PCH, made by loa-render and reused by the others.
# Only system headers (OSG, GoogleTest, the standard library) are precompiled, never the
# project's own, so an edit of an osgLoA header does not rebuild a PCH.
#
# The sanitized build (scripts/test --sanitize) turns it off: there every source is compiled
# on its own includes, so a missing #include that a PCH would hide still fails a build that
# runs regularly (docs/reliability.md).
option(OSGLOA_PRECOMPILED_HEADERS "Precompile the OSG, GoogleTest and standard headers" ON)
if(OSGLOA_SANITIZE)
    set(OSGLOA_PRECOMPILED_HEADERS OFF)
endif()

set(_loa_pch_std <algorithm> <array> <cmath> <cstdint> <cstdio> <cstdlib> <cstring> <fstream>
    <functional> <iostream> <limits> <map> <memory> <mutex> <set> <sstream> <stdexcept> <string>
    <unordered_map> <utility> <vector>)
set(_loa_pch_osg <osg/Camera> <osg/Geode> <osg/Geometry> <osg/Group> <osg/MatrixTransform>
    <osg/Notify> <osg/NodeVisitor> <osg/Program> <osg/StateSet> <osg/Texture2D> <osg/Uniform>
    <osg/ValueObject> <osgDB/FileNameUtils> <osgDB/FileUtils> <osgDB/ReadFile> <osgDB/Registry>
    <osgDB/WriteFile>)

# osgloa_precompile_headers(TARGET FAMILY): FAMILY is library, serializers, tests or tools.
# The first target of a shared family (tests, tools) makes the PCH; the others reuse it.
function(osgloa_precompile_headers target family)
    if(NOT OSGLOA_PRECOMPILED_HEADERS)
        return()
    endif()
    if(family STREQUAL "library")
        target_precompile_headers(${target} PRIVATE ${_loa_pch_std} ${_loa_pch_osg})
    elseif(family STREQUAL "serializers")
        target_precompile_headers(${target} PRIVATE ${_loa_pch_std} ${_loa_pch_osg} <osgDB/ObjectWrapper>
                                  <osgDB/Serializer> <osgDB/InputStream> <osgDB/OutputStream>)
    elseif(family STREQUAL "tests" OR family STREQUAL "tools")
        get_property(_owner GLOBAL PROPERTY OSGLOA_PCH_OWNER_${family})
        if(_owner)
            target_precompile_headers(${target} REUSE_FROM ${_owner})
        else()
            set(_extra)
            if(family STREQUAL "tests")
                set(_extra <gtest/gtest.h>)
            endif()
            target_precompile_headers(${target} PRIVATE ${_loa_pch_std} ${_loa_pch_osg} ${_extra})
            set_property(GLOBAL PROPERTY OSGLOA_PCH_OWNER_${family} ${target})
        endif()
    else()
        message(FATAL_ERROR "osgloa_precompile_headers: unknown family '${family}'")
    endif()
endfunction()
