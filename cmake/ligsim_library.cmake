# ligsim_library(NAME SOURCES ... DEPS ...): one static library per source folder,
# including from the repository root, with the project's warning flags.
function(ligsim_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  target_compile_options(${name} PRIVATE -Wall -Wextra -Wpedantic)
endfunction()

# ligsim_test(NAME SOURCES ... DEPS ... [FIXTURES f]): one GoogleTest executable per tested
# folder; FIXTURES names ctest fixtures (tests that make their inputs) its tests need.
function(ligsim_test name)
  cmake_parse_arguments(ARG "" "FIXTURES" "SOURCES;DEPS" ${ARGN})
  set(fixtures "")
  if(ARG_FIXTURES)
    set(fixtures FIXTURES_REQUIRED ${ARG_FIXTURES})
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest_main)
  target_compile_options(${name} PRIVATE -Wall -Wextra)
  target_compile_definitions(${name} PRIVATE
    LIGSIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    LIGSIM_BINARY="$<TARGET_FILE:ligsim>")
  gtest_discover_tests(${name} WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
    DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900 ${fixtures})
endfunction()
