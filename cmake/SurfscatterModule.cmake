# One static library per module of src/surfscatter/<module>/, so that the data flow
# (math -> spectrum/material -> surface -> bsdf -> render -> photo) is enforced by the link graph.
set(SURFSCATTER_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
# Math functions never set errno and floating-point exceptions never trap (nothing here reads errno after them or
# enables traps): sqrt becomes one instruction, and loops over the four wavelengths of a path with divisions and
# selects can be vectorised. IEEE results are unchanged (unlike -ffast-math). The modules are position-independent
# (below) but never interposed (static libraries, linked into executables and one Python extension): without
# -fno-semantic-interposition GCC would not inline a module's own non-inline functions into each other.
set(SURFSCATTER_CODEGEN -fno-math-errno -fno-trapping-math -fno-semantic-interposition)

# surfscatter_module(<name> [DEPS <targets>...])
function(surfscatter_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${name}/*.cpp")
  set(target surfscatter_${name})
  if(sources)
    add_library(${target} STATIC ${sources})
    # Position-independent, so that the Python extension (python/) can link the same static libraries.
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_include_directories(${target} PUBLIC "${PROJECT_SOURCE_DIR}/src")
    target_compile_options(${target} PRIVATE ${SURFSCATTER_WARNINGS} ${SURFSCATTER_CODEGEN})
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
    target_compile_definitions(${target} PRIVATE
      SURFSCATTER_SOURCE_DIR="${SURFSCATTER_SOURCE_DIR}")
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE "${PROJECT_SOURCE_DIR}/src")
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  add_library(surfscatter::${name} ALIAS ${target})
endfunction()

# surfscatter_test(<module> [DEPS <targets>...] [LABELS <labels>...]): the labels are joined to the module name.
# Every tests/<module>/*.cpp goes into one GoogleTest executable test_<module>.
function(surfscatter_test name)
  cmake_parse_arguments(ARG "" "" "DEPS;LABELS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${name}/*.cpp")
  if(NOT sources)
    return()
  endif()
  set(target test_${name})
  add_executable(${target} ${sources})
  target_include_directories(${target} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
  target_compile_options(${target} PRIVATE ${SURFSCATTER_WARNINGS})
  if(TARGET surfscatter::${name})
    target_link_libraries(${target} PRIVATE surfscatter::${name})
  endif()
  target_link_libraries(${target} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main GTest::gmock)
  target_compile_definitions(${target} PRIVATE
    SURFSCATTER_SHARED_DATA="${SURFSCATTER_SHARED_DATA}"
    SURFSCATTER_SOURCE_DIR="${SURFSCATTER_SOURCE_DIR}"
    SURFSCATTER_CLI="$<TARGET_FILE:surfscatter>")
  if(name STREQUAL "cli")
    add_dependencies(${target} surfscatter)
    target_compile_definitions(${target} PRIVATE SURFSCATTER_MPIEXEC="${MPIEXEC_EXECUTABLE}")
  endif()
  # One label, e.g. "bsdf-slow": gtest_discover_tests splits a list-valued property into separate arguments
  # (CMake issue 17812), so "bsdf;slow" set the label "bsdf" only and `ctest -LE slow` excluded nothing.
  list(PREPEND ARG_LABELS ${name})
  list(JOIN ARG_LABELS "-" label)
  gtest_discover_tests(${target}
    PROPERTIES LABELS "${label}"
    DISCOVERY_TIMEOUT 60)
endfunction()
