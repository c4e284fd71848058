# `cmake --install` of the build into a fresh prefix, then `import surfscatter` from that prefix alone (run by
# ctest as python_install). Variables: BUILD_DIR, PREFIX, SITE (package directory relative to PREFIX), PYTHON.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${status})")
endif()
foreach(file __init__.py)
  if(NOT EXISTS "${PREFIX}/${SITE}/surfscatter/${file}")
    message(FATAL_ERROR "${PREFIX}/${SITE}/surfscatter/${file} was not installed")
  endif()
endforeach()
set(check [=[
import sys, surfscatter
assert surfscatter.__file__.startswith(sys.argv[1]), surfscatter.__file__
assert abs(surfscatter.Conductor("Au").ior(550).imag - 2.32) < 0.2
print("installed", surfscatter.__file__)
]=])
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${PREFIX}/${SITE}" "${PYTHON}" -c "${check}" "${PREFIX}"
  WORKING_DIRECTORY "${PREFIX}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "import surfscatter from ${PREFIX}/${SITE} failed (${status})")
endif()
