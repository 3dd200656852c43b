# atssim_add_library(NAME SOURCES... DEPS...) — one static library per
# pipeline stage; a stage links only the stages to its left (DESIGN.md).
function(atssim_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/lib)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
endfunction()

# atssim_add_test(NAME SOURCES... DEPS...) — one Catch2 executable per stage,
# registered with ctest test by test.
function(atssim_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} Catch2::Catch2WithMain)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  set(props ENVIRONMENT "POCL_CACHE_DIR=${ATSSIM_TEST_POCL_CACHE}")
  if(ARG_LABELS)
    list(APPEND props LABELS "${ARG_LABELS}")
  endif()
  catch_discover_tests(${name}
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
    PROPERTIES ${props}
    DISCOVERY_MODE PRE_TEST)
endfunction()
