include(${CMAKE_CURRENT_LIST_DIR}/AmosTestLabels.cmake)

# amos_add_module(<name> [DEPS <target>...] [TEST_DEPS <target>...] [EXCLUDE <regex>])
# Builds src/amos/<name>/*.cc (except *_test.cc and *_bench.cc) into the static library amos_<name>
# (alias amos::<name>). With AMOS_BUILD_TESTS, every *_test.cc beside it goes into amos_<name>_tests, whose
# GoogleTest cases are registered with CTest as "<name>/<Suite>.<Case>", labelled and given a timeout by
# amos_label_tests (AmosTestLabels.cmake).
function(amos_add_module name)
  cmake_parse_arguments(ARG "" "EXCLUDE" "DEPS;TEST_DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  list(FILTER sources EXCLUDE REGEX "_(test|bench)\\.cc$")
  if(ARG_EXCLUDE)
    list(FILTER sources EXCLUDE REGEX "${ARG_EXCLUDE}")
  endif()
  if(NOT sources)
    message(STATUS "module ${name}: no sources yet, skipped")
    return()
  endif()
  add_library(amos_${name} STATIC ${sources})
  add_library(amos::${name} ALIAS amos_${name})
  target_include_directories(amos_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>)
  target_link_libraries(amos_${name} PUBLIC ${ARG_DEPS})
  target_compile_features(amos_${name} PUBLIC cxx_std_17)

  if(AMOS_BUILD_TESTS)
    file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cc)
    if(ARG_EXCLUDE AND tests)
      list(FILTER tests EXCLUDE REGEX "${ARG_EXCLUDE}")
    endif()
    amos_add_module_tests(${name} amos_${name} ${tests} DEPS ${ARG_TEST_DEPS})
  endif()
endfunction()

# amos_add_module_tests(<name> <library> <test source>... [DEPS <target>...])
# The test program amos_<name>_tests of <library> from the given sources (none: nothing), its cases registered
# with CTest as "<module>/<Suite>.<Case>" (<module>: <name> up to its first "_").
function(amos_add_module_tests name library)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  set(tests ${ARG_UNPARSED_ARGUMENTS})
  if(NOT tests)
    return()
  endif()
  string(REGEX REPLACE "_.*" "" module ${name})
  add_executable(amos_${name}_tests ${tests})
  amos_test_program_options(amos_${name}_tests)
  target_link_libraries(amos_${name}_tests PRIVATE ${library} ${ARG_DEPS} ${OpenCV_LIBS} GTest::gtest
    GTest::gtest_main)
  target_compile_definitions(amos_${name}_tests PRIVATE
    AMOS_DATA_DIR="${AMOS_DATA_DIR}" AMOS_MODELS_DIR="${AMOS_MODELS_DIR}" AMOS_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    AMOS_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(amos_${name}_tests TEST_PREFIX "${module}/" DISCOVERY_TIMEOUT 60
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR})
  amos_label_tests(amos_${name}_tests ${tests})
endfunction()

# amos_add_module_part(<module> <part> MATCH <regex> [DEPS <target>...] [TEST_DEPS <target>...])
# The sources of src/amos/<module>/ whose names match <regex> (those amos_add_module(<module> ... EXCLUDE <regex>)
# left out) as the static library amos_<module>_<part>, on amos_<module> and DEPS, with their tests in
# amos_<module>_<part>_tests ("<module>/<Suite>.<Case>"). For the sources that need a library the module's users
# must not load (the dense map's Open3D: they go into the dense plugin, run/dense_plugin.h).
function(amos_add_module_part module part)
  cmake_parse_arguments(ARG "" "MATCH" "DEPS;TEST_DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  list(FILTER sources INCLUDE REGEX "${ARG_MATCH}")
  set(tests ${sources})
  list(FILTER sources EXCLUDE REGEX "_(test|bench)\\.cc$")
  list(FILTER tests INCLUDE REGEX "_test\\.cc$")
  set(target amos_${module}_${part})
  add_library(${target} STATIC ${sources})
  add_library(amos::${module}_${part} ALIAS ${target})
  target_link_libraries(${target} PUBLIC amos_${module} ${ARG_DEPS})
  if(AMOS_BUILD_TESTS)
    amos_add_module_tests(${module}_${part} ${target} ${tests} DEPS ${ARG_TEST_DEPS})
  endif()
endfunction()
