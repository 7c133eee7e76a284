# Runs mvcl-lens-conformance and checks its exit status and output, for the runner's tests in
# tests/CMakeLists.txt (ctest alone can check one of the two).
#
#   cmake -DRUNNER=<exe> "-DARGS=a|b" -DSTATUS=<n> -DOUTPUT_MATCHES=<regex> [-DPLUGIN_PATH=<dirs>]
#         -P CheckConformanceRunner.cmake
#
# ARGS are separated by '|' (a ';' does not survive add_test).
cmake_minimum_required(VERSION 3.25)
if(DEFINED PLUGIN_PATH)
    set(ENV{MVCL_PLUGIN_PATH} "${PLUGIN_PATH}")
else()
    unset(ENV{MVCL_PLUGIN_PATH})
endif()
string(REPLACE "|" ";" ARGS "${ARGS}")
execute_process(COMMAND ${RUNNER} ${ARGS} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE status)
set(all "${out}${err}")
if(NOT status STREQUAL "${STATUS}")
    message(FATAL_ERROR "mvcl-lens-conformance ${ARGS}: exit status ${status}, expected ${STATUS}\n${all}")
endif()
if(NOT all MATCHES "${OUTPUT_MATCHES}")
    message(FATAL_ERROR "mvcl-lens-conformance ${ARGS}: output does not match '${OUTPUT_MATCHES}'\n${all}")
endif()
message("mvcl-lens-conformance ${ARGS}: exit status ${status} and output as expected")
