# The fuzz targets, one list for both builds that use them:
#  - OSGLOA_FUZZ_MODE "libfuzzer" (tests/fuzz/CMakeLists.txt, clang, OSGLOA_BUILD_FUZZERS):
#    each target linked with libFuzzer, ASan and UBSan; scripts/fuzz runs them;
#  - OSGLOA_FUZZ_MODE "replay" (tests/CMakeLists.txt, the normal build): each target linked with
#    StandaloneFuzzMain.cpp as Replay<Target>, and a CTest test FuzzReplay.<Target> that runs it
#    over the target's seed corpus and its reproducers (tests/fuzz/crashes/<corpus>/), so every
#    input that once crashed, hung or blew up stays a regression test, in CI as everywhere.
#
# osgloa_fuzz_target(NAME CORPUS SEEDS... SOURCES src... OBJECTS lib... LIBS lib...): CORPUS names
# the folder under tests/fuzz/crashes/ (and, unless SEEDS says otherwise, under tests/fuzz/corpus/).
# OBJECTS names the plugins' object libraries that hold SOURCES compiled: the replay build links
# those objects when the plugin is built, rather than compiling the reader a second time; the
# libFuzzer build always compiles SOURCES itself, instrumented.
set(_fuzz_dir "${PROJECT_SOURCE_DIR}/tests/fuzz")
find_package(nlohmann_json REQUIRED)
find_package(GDAL REQUIRED)
find_package(BZip2 REQUIRED)

function(osgloa_fuzz_target name corpus)
    cmake_parse_arguments(F "" "" "SEEDS;SOURCES;OBJECTS;LIBS" ${ARGN})
    if(NOT F_SEEDS)
        set(F_SEEDS "${_fuzz_dir}/corpus/${corpus}")
    endif()
    if(OSGLOA_FUZZ_MODE STREQUAL "libfuzzer")
        add_executable(${name} ${_fuzz_dir}/${name}.cpp ${F_SOURCES})
        target_compile_options(${name} PRIVATE -fsanitize=fuzzer ${OSGLOA_FUZZ_COVERAGE} ${OSGLOA_FUZZ_SANITIZE}
                                               -Wall -Wextra -Wpedantic)
        target_link_options(${name} PRIVATE -fsanitize=fuzzer ${OSGLOA_FUZZ_SANITIZE})
        set(_target ${name})
    else()
        set(_target Replay${name})
        set(_compiled ${F_SOURCES})
        if(F_OBJECTS)
            set(_compiled)
            foreach(_objects IN LISTS F_OBJECTS)
                if(NOT TARGET ${_objects})
                    set(_compiled ${F_SOURCES})
                    break()
                endif()
                list(APPEND _compiled $<TARGET_OBJECTS:${_objects}>)
            endforeach()
        endif()
        add_executable(${_target} ${_fuzz_dir}/${name}.cpp ${_fuzz_dir}/StandaloneFuzzMain.cpp ${_compiled})
        osgloa_set_warnings(${_target})
        set(_inputs ${F_SEEDS})
        if(EXISTS "${_fuzz_dir}/crashes/${corpus}")
            list(APPEND _inputs "${_fuzz_dir}/crashes/${corpus}")
        endif()
        add_test(NAME FuzzReplay.${name} COMMAND ${_target} ${_inputs})
        set_tests_properties(FuzzReplay.${name} PROPERTIES LABELS unit TIMEOUT ${OSGLOA_TEST_TIMEOUT}
                             ENVIRONMENT "OSG_LIBRARY_PATH=${CMAKE_BINARY_DIR}/lib")
    endif()
    target_include_directories(${_target} PRIVATE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${_target} PRIVATE osgLoA::osgLoA ${F_LIBS})
    # The targets that read OSG files need our serializer plugin built.
    add_dependencies(${_target} osgdb_serializers_osgloa)
    set_property(GLOBAL APPEND PROPERTY OSGLOA_FUZZ_TARGETS ${_target})
endfunction()

set(_loa_fuzz_prefix "")
if(NOT OSGLOA_FUZZ_MODE STREQUAL "libfuzzer")
    set(_loa_fuzz_prefix Replay)
endif()
set(_osm "${PROJECT_SOURCE_DIR}/plugins/osm")
osgloa_fuzz_target(ScenarioFileFuzzer scenario
                   SEEDS "${PROJECT_SOURCE_DIR}/data/scenarios" "${_fuzz_dir}/corpus/scenario")
osgloa_fuzz_target(CityJsonFuzzer cityjson
                   SOURCES ${PROJECT_SOURCE_DIR}/plugins/cityjson/CityJsonReader.cpp OBJECTS osgloa_cityjson_reader
                   LIBS nlohmann_json::nlohmann_json)
osgloa_fuzz_target(OsmFuzzer osm
                   SOURCES ${_osm}/OsmFile.cpp ${_osm}/OsmTags.cpp ${_osm}/OsmScene.cpp
                   OBJECTS osgloa_osm_file osgloa_osm_scene
                   LIBS GDAL::GDAL PROJ::proj BZip2::BZip2 osgLoA_osmium)
osgloa_fuzz_target(OsmSceneFuzzer osmscene
                   SOURCES ${_osm}/OsmTags.cpp ${_osm}/OsmScene.cpp OBJECTS osgloa_osm_scene
                   LIBS GDAL::GDAL PROJ::proj)
osgloa_fuzz_target(ModelFuzzer model)
osgloa_fuzz_target(RuleSetFuzzer rules)
osgloa_fuzz_target(LoaFileFuzzer loa)
add_dependencies(${_loa_fuzz_prefix}LoaFileFuzzer osgdb_loa)
osgloa_fuzz_target(FilterCacheFuzzer filtercache)
