# ctest script: installs the gproj build GPROJ_BINARY_DIR into WORK_DIR/prefix, configures and
# builds GPROJ_SOURCE_DIR/examples against it with find_package(gproj) and the compiler
# CXX_COMPILER (the one gproj was built with), runs the example.
# Fails with the step's output when any step fails.
function(run_step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name} failed (${rc}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run_step(install ${CMAKE_COMMAND} --install ${GPROJ_BINARY_DIR} --prefix ${prefix})
file(GLOB_RECURSE config ${prefix}/*/gprojConfig.cmake)
if(NOT EXISTS ${prefix}/include/gproj/solver/term.h OR NOT config)
  message(FATAL_ERROR "the install lacks include/gproj/solver/term.h or the CMake package")
endif()
run_step(configure ${CMAKE_COMMAND} -S ${GPROJ_SOURCE_DIR}/examples -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
run_step(build ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run_step(run ${WORK_DIR}/build/custom_constraint)
if(NOT step_output MATCHES "objective: guided projection")
  message(FATAL_ERROR "the example printed no objective line:\n${step_output}")
endif()
message(STATUS "${step_output}")
