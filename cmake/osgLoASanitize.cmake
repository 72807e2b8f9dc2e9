# OSGLOA_SANITIZE: every target of the project (library, plugins, tools, tests) compiled and
# linked with AddressSanitizer and UndefinedBehaviorSanitizer; any undefined behaviour aborts
# (no recovery), so a finding fails the test that hit it. scripts/test --sanitize builds
# build-sanitize with it and runs the whole suite; docs/reliability.md has the result.
#
# Programs that are not ours (the stock osgconv and osgviewer) load our instrumented plugins
# only with the ASan runtime preloaded; OSGLOA_SANITIZER_PRELOAD is that runtime's path, which
# the tests put in LD_PRELOAD for them (loatest::stockTool) and docs/reliability.md tells users.
if(NOT OSGLOA_SANITIZE)
    return()
endif()
if(OSGLOA_BUILD_FUZZERS)
    message(FATAL_ERROR "OSGLOA_SANITIZE and OSGLOA_BUILD_FUZZERS are separate builds "
                        "(build-sanitize, build-fuzz); configure one of them")
endif()
set(_loa_sanitize -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
add_compile_options(${_loa_sanitize})
add_link_options(${_loa_sanitize})
# osgDB unloads plugins at exit, before LeakSanitizer looks: a leak in a plugin (or in a library
# only a plugin pulls in, such as libcitygml) would be reported from "<unknown module>", which
# no suppression can name. Our shared objects stay loaded (-z nodelete), so stacks keep names.
add_link_options(-Wl,-z,nodelete)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # GCC's flow analysis sees through ASan's instrumentation badly: with it, GCC 12 reports
    # -Wmaybe-uninitialized on std::string members of OSG's serializer templates
    # (EnumByNameSerializer.h, BoundedListSerializer.h) that the normal build does not; GCC's
    # manual warns that sanitizers make such warnings unreliable. Off here, kept in the
    # normal build, where -Werror still enforces it.
    add_compile_options(-Wno-maybe-uninitialized)
endif()
execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libasan.so
                OUTPUT_VARIABLE OSGLOA_SANITIZER_PRELOAD OUTPUT_STRIP_TRAILING_WHITESPACE)
get_filename_component(OSGLOA_SANITIZER_PRELOAD "${OSGLOA_SANITIZER_PRELOAD}" REALPATH)
if(NOT EXISTS "${OSGLOA_SANITIZER_PRELOAD}")
    message(FATAL_ERROR "OSGLOA_SANITIZE: the compiler names no ASan runtime (${OSGLOA_SANITIZER_PRELOAD})")
endif()
message(STATUS "osgLoA: sanitized build (ASan + UBSan); stock OSG tools need LD_PRELOAD=${OSGLOA_SANITIZER_PRELOAD}")
