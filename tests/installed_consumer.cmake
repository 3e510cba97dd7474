# Installs pamkit into <build>/consumer/<EXAMPLE>/prefix, then configures, builds and runs
# examples/<EXAMPLE> (default: controller) against that installation with find_package(pamkit); its
# warnings are errors when the build has PAMKIT_WERROR (WERROR). MUSCLE_ONLY=ON configures the
# example as on a machine without SUNDIALS and libserialport: find_package of either fails there.
if(NOT EXAMPLE)
  set(EXAMPLE controller)
endif()
set(work ${BUILD_DIR}/consumer/${EXAMPLE})
set(without)
if(MUSCLE_ONLY)
  set(without -DCMAKE_DISABLE_FIND_PACKAGE_SUNDIALS=ON -DCMAKE_DISABLE_FIND_PACKAGE_LibSerialPort=ON)
endif()
file(REMOVE_RECURSE ${work})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${work}/prefix --component development)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/${EXAMPLE} -B ${work}/build -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${work}/prefix -DCMAKE_COMPILE_WARNING_AS_ERROR=${WERROR} ${without})
run(${CMAKE_COMMAND} --build ${work}/build)
run(${work}/build/${EXAMPLE})
