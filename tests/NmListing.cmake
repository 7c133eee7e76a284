# Shared by the symbol checks run as ctests (core/CheckExportedSymbols.cmake,
# tracer/CheckIsaSymbols.cmake): nm's listing of a file as a CMake list of lines.
#
#   nm_lines(<out_var> <file> <nm option>...)
# Fails naming the file when nm fails. Semicolons in symbols are escaped so that each line stays
# one element.
function(nm_lines out_var file)
    execute_process(COMMAND ${NM} ${ARGN} ${file}
        OUTPUT_VARIABLE listing ERROR_VARIABLE problem RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
        message(FATAL_ERROR "${file}: nm failed (${status}): ${problem}")
    endif()
    string(REPLACE ";" "\\;" listing "${listing}")
    string(REPLACE "\n" ";" lines "${listing}")
    set(${out_var} "${lines}" PARENT_SCOPE)
endfunction()
