# ctest script: installs the gproj build GPROJ_BINARY_DIR into WORK_DIR/prefix (checking that
# no internal/ header is installed), builds GPROJ_SOURCE_DIR/examples against it with
# find_package(gproj) and the compiler CXX_COMPILER (the one gproj was built with), runs the
# example, and compiles every installed header in one consumer translation unit; both with
# headers named like gproj's on the include path. Fails with the step's output when any step
# fails. Also checks that gproj serve's web app and examples are installed and found.
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
file(GLOB_RECURSE internal ${prefix}/include/gproj/*)
list(FILTER internal INCLUDE REGEX "/internal/")
if(internal)
  message(FATAL_ERROR "internal headers were installed: ${internal}")
endif()
# gproj serve's web app and examples are installed beside the program, and the installed program
# reads them from there (its --help names the folders it defaults to).
foreach(file share/gproj/web/app/index.html share/gproj/web/app/app.js
    share/gproj/examples/noisy_grid_21x21.obj bin/gproj)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()
if(EXISTS ${GPROJ_SOURCE_DIR}/web/node_modules/three/build/three.module.js AND
    NOT EXISTS ${prefix}/share/gproj/web/node_modules/three/build/three.module.js)
  message(FATAL_ERROR "the install lacks the web app's three.js")
endif()
run_step(serve_help ${prefix}/bin/gproj serve --help)
foreach(folder web examples)
  if(NOT step_output MATCHES "${prefix}/share/gproj/${folder}")
    message(FATAL_ERROR "the installed gproj serve does not default to its installed ${folder}:\n"
      "${step_output}")
  endif()
endforeach()

# A project with headers of the same names as gproj's on its include path: gproj's own headers
# must still find each other (they are included as "gproj/...").
foreach(header solver/problem.h solver/term.h common/input_error.h geometry/mesh/quad_shape.h
    problems/run/registry.h)
  file(WRITE ${WORK_DIR}/shadow/${header} "#error a project's own ${header} shadowed gproj's\n")
endforeach()
run_step(configure ${CMAKE_COMMAND} -S ${GPROJ_SOURCE_DIR}/examples -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
  "-DCMAKE_CXX_FLAGS=-I${WORK_DIR}/shadow")
run_step(build ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run_step(run ${WORK_DIR}/build/custom_constraint)
if(NOT step_output MATCHES "objective: guided projection")
  message(FATAL_ERROR "the example printed no objective line:\n${step_output}")
endif()
message(STATUS "${step_output}")

# Every installed header compiles in a consumer's translation unit, included as <gproj/...>,
# with the shadowing headers above on the include path.
file(GLOB_RECURSE headers RELATIVE ${prefix}/include ${prefix}/include/gproj/*.h)
set(source "")
foreach(header ${headers})
  string(APPEND source "#include <${header}>\n")
endforeach()
string(APPEND source "int main() { return 0; }\n")
file(WRITE ${WORK_DIR}/headers/all_headers.cc "${source}")
file(WRITE ${WORK_DIR}/headers/CMakeLists.txt
  "cmake_minimum_required(VERSION 3.20)\nproject(gproj_headers LANGUAGES CXX)\n"
  "set(CMAKE_CXX_STANDARD 17)\nfind_package(gproj 0.1 REQUIRED)\n"
  "add_executable(all_headers all_headers.cc)\n"
  "target_link_libraries(all_headers PRIVATE gproj::gproj)\n")
run_step(configure_headers ${CMAKE_COMMAND} -S ${WORK_DIR}/headers -B ${WORK_DIR}/headers/build
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
  "-DCMAKE_CXX_FLAGS=-I${WORK_DIR}/shadow")
run_step(build_headers ${CMAKE_COMMAND} --build ${WORK_DIR}/headers/build)
list(LENGTH headers count)
message(STATUS "${count} installed headers compile together as <gproj/...>")
