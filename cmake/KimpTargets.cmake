# Helpers shared by every target: C++17, include root, warnings (errors in CI).

function(kimp_setup_target target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local
                                           -Wnon-virtual-dtor -Woverloaded-virtual)
  if(KIMP_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# kimp_add_test(NAME name SOURCES a.cc b.cc LIBS kimp::lumped LABELS physics fem [TIMEOUT s])
# One GoogleTest executable; every TEST becomes a ctest test carrying every label (unit, physics,
# fem, slow, mpi, e2e). LABEL x is LABELS x with one label. Tests run in the source directory with
# KIMP_SOURCE_DIR set; the build directory is compiled in as KIMP_BINARY_DIR.
function(kimp_add_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT;LABEL" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  kimp_setup_target(${T_NAME})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} kimp::test_support GTest::gtest GTest::gtest_main)
  target_compile_definitions(${T_NAME} PRIVATE KIMP_BINARY_DIR="${PROJECT_BINARY_DIR}")
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  set(labels ${T_LABEL} ${T_LABELS})
  if(NOT labels)
    set(labels unit)
  endif()
  gtest_discover_tests(${T_NAME}
    TEST_PREFIX "${T_NAME}."
    TEST_LIST ${T_NAME}_TESTS
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES TIMEOUT ${T_TIMEOUT} ENVIRONMENT "KIMP_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
    DISCOVERY_TIMEOUT 60)
  # Labels after discovery: gtest_discover_tests() flattens a list-valued property (only the first
  # label would survive). ctest includes this file after the discovered tests' own file.
  set(labels_file "${CMAKE_CURRENT_BINARY_DIR}/${T_NAME}_labels.cmake")
  file(WRITE "${labels_file}"
       "if(${T_NAME}_TESTS)\n"
       "  set_tests_properties(\${${T_NAME}_TESTS} PROPERTIES LABELS \"${labels}\")\n"
       "endif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${labels_file}")
endfunction()

# kimp_add_library(target alias sources...): a compiled library, or a header-only INTERFACE
# library while a directory has no sources yet.
function(kimp_add_library target alias)
  if(ARGN)
    add_library(${target} ${ARGN})
    kimp_setup_target(${target})
    set(kind PUBLIC)
  else()
    add_library(${target} INTERFACE)
    target_compile_features(${target} INTERFACE cxx_std_17)
    target_include_directories(${target} INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>)
  endif()
  add_library(${alias} ALIAS ${target})
endfunction()

# Scope keyword to use with target_link_libraries for a target made by kimp_add_library.
function(kimp_link target)
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_link_libraries(${target} INTERFACE ${ARGN})
  else()
    target_link_libraries(${target} PUBLIC ${ARGN})
  endif()
endfunction()

# The glue layers (base, io, report, app, server, cli and the two executables) parse scenes,
# dispatch commands and write files; the physics is computed in the engines (lumped, fit,
# geometry, fem), which keep the build type's optimisation. Compiled at -O1 the glue takes about
# 30 % less compile time and runs no measurably slower (docs/performance.md, "Build CPU of `kimp`
# and `kimp-fem`").
# Without -ffast-math and without FMA in the target architecture, the optimisation level changes
# no floating-point result. Empty: the build type's level everywhere.
set(KIMP_GLUE_OPTIMIZATION "-O1" CACHE STRING
    "Optimisation flag of the glue layers in Release builds (empty: the build type's)")

# Unity builds of the glue layers and of lumped/: CMake compiles a target's sources in batches of
# KIMP_UNITY_BATCH_SIZE, one translation unit per batch, so that the heavy headers every such
# source includes (nlohmann-json, fmt, spdlog, yaml-cpp, CLI11, Eigen) are parsed once per batch
# instead of once per source (docs/performance.md, "Unity builds"). A source whose file-scope
# names (anonymous namespace, static) clash with another source's of its target is kept out of
# the batches with kimp_unity_exclude(). A source with source-file compile definitions is
# compiled on its own by CMake.
option(KIMP_UNITY_BUILD "Compile the glue layers and lumped/ in batches (unity builds)" ON)
set(KIMP_UNITY_BATCH_SIZE "8" CACHE STRING "Sources per unity translation unit")

# kimp_unity_exclude(sources...): compile these sources on their own in a unity build (called in
# the directory that makes their target).
function(kimp_unity_exclude)
  set_source_files_properties(${ARGN} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
endfunction()

# kimp_unity_target(targets...): compile these targets in unity batches when KIMP_UNITY_BUILD is on.
function(kimp_unity_target)
  if(KIMP_UNITY_BUILD)
    set_target_properties(${ARGN} PROPERTIES UNITY_BUILD ON
                                             UNITY_BUILD_BATCH_SIZE ${KIMP_UNITY_BATCH_SIZE})
  endif()
endfunction()

# kimp_glue_target(targets...): compile these targets at KIMP_GLUE_OPTIMIZATION (Release only),
# in unity batches.
function(kimp_glue_target)
  foreach(target ${ARGN})
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "INTERFACE_LIBRARY")
      continue()
    endif()
    if(KIMP_GLUE_OPTIMIZATION)
      target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:${KIMP_GLUE_OPTIMIZATION}>)
    endif()
    kimp_unity_target(${target})
  endforeach()
endfunction()

# deal.II's headers are precompiled in fem/ (fem/CMakeLists.txt). Measured and not kept: a
# precompiled header of nlohmann-json, fmt and the standard headers for io/ (-O1) saved about what
# building it cost (31.3 s against 31.6 s for io/'s 16 sources).
option(KIMP_PRECOMPILED_HEADERS "Precompile deal.II's headers in fem/" ON)
# ccache caches a source compiled with a precompiled header only with the sloppiness
# pch_defines,time_macros (no kimp source uses __DATE__ or __TIME__): with ccache as the compiler
# launcher, kimp's compilations run it with these added to the configured sloppiness.
if(KIMP_PRECOMPILED_HEADERS AND CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache")
  list(GET CMAKE_CXX_COMPILER_LAUNCHER 0 kimp_ccache)
  execute_process(COMMAND ${kimp_ccache} --get-config sloppiness
                  OUTPUT_VARIABLE kimp_sloppiness OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  string(REPLACE " " "" kimp_sloppiness "${kimp_sloppiness}")
  string(REPLACE "," ";" kimp_sloppiness "${kimp_sloppiness}")
  list(APPEND kimp_sloppiness pch_defines time_macros)
  list(REMOVE_DUPLICATES kimp_sloppiness)
  list(JOIN kimp_sloppiness "," kimp_sloppiness)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env CCACHE_SLOPPINESS=${kimp_sloppiness}
                                  ${CMAKE_CXX_COMPILER_LAUNCHER})
endif()

# The linker: GNU gold (binutils) links kimp-fem (deal.II, Trilinos, p4est, OpenMPI) in ~1.3 s of
# CPU where the default BFD linker takes ~17 s; every test executable linking the FEM engine pays
# that too. Empty: the compiler's default linker.
set(KIMP_LINKER "gold" CACHE STRING "Linker passed as -fuse-ld= (empty: the compiler's default)")
if(KIMP_LINKER)
  include(CheckLinkerFlag)
  check_linker_flag(CXX -fuse-ld=${KIMP_LINKER} KIMP_LINKER_WORKS_${KIMP_LINKER})
  if(KIMP_LINKER_WORKS_${KIMP_LINKER})
    add_link_options(-fuse-ld=${KIMP_LINKER})
  else()
    message(STATUS "kimp: the linker ${KIMP_LINKER} does not work here: the default one links")
  endif()
endif()
