# Builds examples against an installed pamkit, as a user would, and runs each.
#   -DEXAMPLES=a,b    the folders of examples/ to build, comma-separated (default: simulation)
#   -DMINIMAL=ON      install a pamkit configured from SOURCE_DIR with -DPAMKIT_BUILD_LIBRARY=OFF and
#                     SUNDIALS, pybind11, Python, Catch2, toml++ and libserialport out of CMake's
#                     reach (its find_package of each fails), instead of installing BUILD_DIR; the
#                     examples are configured with SUNDIALS and libserialport out of reach too, and
#                     realtime_controller with toml++ as well (it needs Boost's headers alone)
# Warnings are errors when the build has PAMKIT_WERROR (WERROR).
if(NOT EXAMPLES)
  set(EXAMPLES simulation)
endif()
string(REPLACE "," ";" EXAMPLES "${EXAMPLES}")
if(MINIMAL)
  set(work ${BUILD_DIR}/consumer/minimal)
else()
  set(work ${BUILD_DIR}/consumer/full)
endif()
file(REMOVE_RECURSE ${work})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}")
  endif()
endfunction()

set(unreachable_for_examples -DCMAKE_DISABLE_FIND_PACKAGE_SUNDIALS=ON -DCMAKE_DISABLE_FIND_PACKAGE_LibSerialPort=ON)
if(MINIMAL)
  set(unreachable ${unreachable_for_examples} -DCMAKE_DISABLE_FIND_PACKAGE_pybind11=ON
      -DCMAKE_DISABLE_FIND_PACKAGE_Python=ON -DCMAKE_DISABLE_FIND_PACKAGE_Catch2=ON
      -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${work}/pamkit -G ${GENERATOR} --no-warn-unused-cli -DPAMKIT_BUILD_LIBRARY=OFF
      -DCMAKE_COMPILE_WARNING_AS_ERROR=${WERROR} ${unreachable})
  run(${CMAKE_COMMAND} --build ${work}/pamkit)
  run(${CMAKE_COMMAND} --install ${work}/pamkit --prefix ${work}/prefix --component development)
else()
  set(unreachable_for_examples)
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${work}/prefix --component development)
endif()

foreach(example IN LISTS EXAMPLES)
  set(options ${unreachable_for_examples})
  if(MINIMAL AND example STREQUAL "realtime_controller")
    list(APPEND options -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON)
  endif()
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/${example} -B ${work}/${example} -G ${GENERATOR} --no-warn-unused-cli
      -DCMAKE_PREFIX_PATH=${work}/prefix -DCMAKE_COMPILE_WARNING_AS_ERROR=${WERROR} ${options})
  run(${CMAKE_COMMAND} --build ${work}/${example})
  run(${work}/${example}/${example})
endforeach()
