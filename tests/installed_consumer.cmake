# Installs pamkit into <build>/consumer/prefix, then configures, builds and runs
# examples/controller against that installation with find_package(pamkit); its warnings are errors
# when the build has PAMKIT_WERROR (WERROR).
set(work ${BUILD_DIR}/consumer)
file(REMOVE_RECURSE ${work})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${work}/prefix --component development)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/controller -B ${work}/build -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${work}/prefix -DCMAKE_COMPILE_WARNING_AS_ERROR=${WERROR})
run(${CMAKE_COMMAND} --build ${work}/build)
run(${work}/build/controller)
