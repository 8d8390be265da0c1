# Small helpers so every component's CMakeLists reads the same way.

# Warnings apply to project code only; generated IDL code gets its own flags.
function(uavmot_set_warnings target)
  # -Wshadow=local is GCC's spelling. GCC 12 reports std::string concatenation at -O3 as
  # -Wrestrict (GCC bug 105329): a false positive.
  set(gnu $<CXX_COMPILER_ID:GNU>)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<${gnu}:-Wshadow=local> -Wnon-virtual-dtor
                                           $<${gnu}:-Wno-restrict>)
  if(UAVMOT_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# Sanitizers apply to every target (generated IDL code included); tools/sanitize.sh and
# tools/fuzz.sh set them. UBSan aborts at its first finding instead of printing and carrying on,
# so a test with undefined behaviour fails. -g1 (line tables only) keeps file:line in every report
# and builds faster than -g, which counts when CI finds them missing from its cache.
if(UAVMOT_SANITIZE)
  add_compile_options(-fsanitize=${UAVMOT_SANITIZE} -fno-omit-frame-pointer -g1)
  if(UAVMOT_SANITIZE MATCHES "undefined")
    add_compile_options(-fno-sanitize-recover=all)
  endif()
  # GCC's flow analysis sees the sanitizers' instrumentation and reports std::regex and std::function
  # internals as maybe-uninitialized (libstdc++ headers, not our code); off in sanitizer builds only.
  add_compile_options($<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  add_link_options(-fsanitize=${UAVMOT_SANITIZE})
endif()

# uavmot_add_library(NAME SOURCES ... DEPS ...)
# A component library: public headers in include/, sources in src/.
function(uavmot_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
                                     PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  uavmot_set_warnings(${name})
endfunction()

# uavmot_add_executable(NAME SOURCES ... DEPS ...)
# A process: `uavmot-<x>` executables become `uavmot <x>` subcommands.
function(uavmot_add_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  uavmot_set_warnings(${name})
  install(TARGETS ${name} RUNTIME DESTINATION bin)
endfunction()

# uavmot_add_gtest(NAME SOURCES ... DEPS ... [LABELS ...] [TIMEOUT s])
# Tests live beside the code they test (components/<x>/tests/).
function(uavmot_add_gtest name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  if(NOT UAVMOT_BUILD_TESTS)
    return()
  endif()
  add_executable(${name} ${ARG_SOURCES})
  # uavmot_build_paths: the source, build and data folders (uavmot/build_paths/build_paths.hpp). Not
  # compile definitions here: an absolute path on a test's command line differs between clones and
  # would make each of its objects miss ccache in every CI clone (components/build_paths).
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} uavmot_build_paths GTest::gtest GTest::gtest_main GTest::gmock)
  # tests/support: helpers every test may use (scratch_dir.hpp: where tests write their files).
  target_include_directories(${name} PRIVATE ${CMAKE_SOURCE_DIR}/tests/support)
  uavmot_set_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  add_test(NAME ${name} COMMAND ${name} WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
  set_tests_properties(${name} PROPERTIES TIMEOUT ${ARG_TIMEOUT} LABELS "${ARG_LABELS}")
endfunction()
