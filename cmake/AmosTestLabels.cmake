# amos_label_tests(<test target> <sources> [ALL <label>...])
# CTest labels and a timeout for every GoogleTest case of <test target> (discovered by gtest_discover_tests with
# the default TEST_LIST), so that `ctest -L unit` runs the fast tests alone and a hung test fails instead of
# waiting. The labels come from each test's source (cmake/test_labels.py: unit, real-data, end-to-end, browser),
# regenerated when a test file changes; a test with several labels gets the longest of their timeouts.
if(AMOS_BUILD_TESTS)
  find_package(Python3 REQUIRED COMPONENTS Interpreter)  # cmake/test_labels.py
endif()

set(AMOS_TEST_TIMEOUT_UNIT 60 CACHE STRING "CTest timeout (s) of a unit test")
set(AMOS_TEST_TIMEOUT_REAL_DATA 300 CACHE STRING "CTest timeout (s) of a test on the shared real data")
set(AMOS_TEST_TIMEOUT_END_TO_END 600 CACHE STRING "CTest timeout (s) of a test that runs the system or program")
set(AMOS_TEST_TIMEOUT_BROWSER 600 CACHE STRING "CTest timeout (s) of a test in a headless browser")

function(amos_label_tests target)
  cmake_parse_arguments(ARG "" "" "ALL" ${ARGN})
  set(sources ${ARG_UNPARSED_ARGUMENTS})
  set(all_args)
  foreach(label IN LISTS ARG_ALL)
    list(APPEND all_args --all ${label})
  endforeach()
  set(labels_file ${CMAKE_CURRENT_BINARY_DIR}/${target}_labels.cmake)
  add_custom_command(OUTPUT ${labels_file}
    COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/cmake/test_labels.py --out ${labels_file} ${all_args} ${sources}
    DEPENDS ${sources} ${PROJECT_SOURCE_DIR}/cmake/test_labels.py
    COMMENT "Labelling the tests of ${target}" VERBATIM)
  add_custom_target(${target}_labels DEPENDS ${labels_file})
  add_dependencies(${target} ${target}_labels)
  # Read by CTest after gtest_discover_tests' own include file (which defines ${target}_TESTS).
  set(apply ${CMAKE_CURRENT_BINARY_DIR}/${target}_apply_labels.cmake)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/apply_test_labels.cmake.in ${apply} @ONLY)
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${apply})
endfunction()
