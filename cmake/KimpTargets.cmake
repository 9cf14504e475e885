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

# kimp_add_test(NAME name SOURCES a.cc b.cc LIBS kimp::lumped LABEL physics [TIMEOUT s])
# One GoogleTest executable; every TEST becomes a ctest test with the label (unit, physics, mpi,
# e2e). Tests run in the source directory with KIMP_SOURCE_DIR set; the build directory is compiled
# in as KIMP_BINARY_DIR. (One label and one environment entry: lists do not survive discovery.)
function(kimp_add_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT;LABEL" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  kimp_setup_target(${T_NAME})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${T_NAME} PRIVATE KIMP_BINARY_DIR="${PROJECT_BINARY_DIR}")
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  if(NOT T_LABEL AND T_LABELS)
    list(GET T_LABELS 0 T_LABEL) # LABELS a b: only the first survives discovery
  elseif(NOT T_LABEL)
    set(T_LABEL unit)
  endif()
  gtest_discover_tests(${T_NAME}
    TEST_PREFIX "${T_NAME}."
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES LABELS ${T_LABEL} TIMEOUT ${T_TIMEOUT} ENVIRONMENT "KIMP_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
    DISCOVERY_TIMEOUT 60)
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
