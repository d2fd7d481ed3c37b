# Helpers shared by every module: one library per module, one test per unit.

set(KELVIN_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
    -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wnull-dereference)

function(kelvin_project_options target)
  target_compile_options(${target} PRIVATE ${KELVIN_WARNINGS})
  if(KELVIN_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(KELVIN_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# kelvin_add_library(<name> SOURCES ... DEPS ...)
# Creates kelvin_<name>, with include paths rooted at the repository.
function(kelvin_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(kelvin_${name} STATIC ${ARG_SOURCES})
  add_library(kelvin::${name} ALIAS kelvin_${name})
  target_include_directories(kelvin_${name} PUBLIC ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/generated)
  target_link_libraries(kelvin_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  kelvin_project_options(kelvin_${name})
endfunction()

# kelvin_add_test(<name> SOURCES ... DEPS ... LABELS unit|validation|slow [TIMEOUT s])
# One GoogleTest executable per unit; the test runs from the build tree with
# KELVIN_SOURCE_DIR and KELVIN_SHARED_DIR in its environment.
function(kelvin_add_test name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_compile_definitions(${name} PRIVATE
    KELVIN_DEFAULT_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    KELVIN_DEFAULT_TOOLS_DIR="${PROJECT_BINARY_DIR}/tools")
  kelvin_project_options(${name})
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  add_test(NAME ${name} COMMAND ${name})
  set_tests_properties(${name} PROPERTIES
    LABELS "${ARG_LABELS}"
    TIMEOUT ${ARG_TIMEOUT}
    ENVIRONMENT "KELVIN_SOURCE_DIR=${PROJECT_SOURCE_DIR};KELVIN_BINARY_DIR=${PROJECT_BINARY_DIR};KELVIN_TOOLS_DIR=${PROJECT_BINARY_DIR}/tools")
endfunction()
