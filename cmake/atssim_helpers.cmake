# atssim_add_library(NAME SOURCES... DEPS...) — one static library per
# pipeline stage (lib/<stage>); a stage links only the stages to its left
# (DESIGN.md).
#
# Each stage gets an include root of its own, build/include_roots/<stage>,
# holding nothing but a link <stage> -> lib/<stage>. The root is PUBLIC, so
# a target sees exactly the roots of the stages it links: an include of a
# stage it may not use ("solver/…" from lib/device) fails to compile.
function(atssim_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  get_filename_component(stage ${CMAKE_CURRENT_SOURCE_DIR} NAME)
  add_library(${name} STATIC ${ARG_SOURCES})
  atssim_include_root(${name} PUBLIC ${stage} ${stage} ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
endfunction()

# The arguments every ctest entry of a Catch2 test passes to its binary.
# -w NoTests: a ctest entry whose filter matches no test case fails (Catch2
# v2 otherwise exits 0 having run nothing); tests/CMakeLists.txt checks it.
set(ATSSIM_CATCH_ARGS -w NoTests)

# atssim_include_root(TARGET SCOPE ROOT PREFIX DIR) — gives TARGET (with
# SCOPE: PUBLIC, PRIVATE or INTERFACE) the include root
# build/include_roots/ROOT, which holds only the link PREFIX -> DIR: the
# target (and, unless PRIVATE, what links it) includes "PREFIX/…" from DIR
# and nothing beside it.
function(atssim_include_root target scope root prefix dir)
  set(path ${PROJECT_BINARY_DIR}/include_roots/${root})
  file(MAKE_DIRECTORY ${path})
  if(NOT EXISTS ${path}/${prefix})
    file(CREATE_LINK ${dir} ${path}/${prefix} SYMBOLIC)
  endif()
  target_include_directories(${target} ${scope} ${path})
endfunction()

# atssim_add_test(NAME SOURCES... DEPS... [LABELS...] [RESOURCE_LOCK lock]) —
# one Catch2 executable per stage, registered with ctest test by test. Tests
# that hold the same RESOURCE_LOCK never run at the same time under ctest -j.
function(atssim_add_test name)
  cmake_parse_arguments(ARG "" "RESOURCE_LOCK" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  set_property(GLOBAL APPEND PROPERTY ATSSIM_TEST_TARGETS ${name})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} Catch2::Catch2WithMain)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  set(props ENVIRONMENT "POCL_CACHE_DIR=${ATSSIM_TEST_POCL_CACHE}")
  if(ARG_LABELS)
    list(APPEND props LABELS "${ARG_LABELS}")
  endif()
  if(ARG_RESOURCE_LOCK)
    list(APPEND props RESOURCE_LOCK ${ARG_RESOURCE_LOCK})
  endif()
  catch_discover_tests(${name}
    EXTRA_ARGS ${ATSSIM_CATCH_ARGS}
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
    PROPERTIES ${props}
    DISCOVERY_MODE PRE_TEST)
  add_test(NAME ${name}.test_names_have_no_semicolon
           COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:${name}> -P ${PROJECT_SOURCE_DIR}/cmake/check_test_names.cmake)
endfunction()
