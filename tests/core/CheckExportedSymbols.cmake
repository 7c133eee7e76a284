# Fails when a shared library exports internal symbols: mvcl::detail, mvcl::gltf, tinygltf or
# nlohmann (the framework's internals and the libraries it is built from). libmvcl.so exports
# only its public API (mvcl/core/Export.h).
#
#   cmake -DNM=<nm> -DLIBRARY=<file.so> -P CheckExportedSymbols.cmake
#
# Prints "<file>: <n> exported symbols, <m> internal" and, when m > 0, the first of them.
cmake_minimum_required(VERSION 3.25)
if(NOT NM OR NOT LIBRARY)
    message(FATAL_ERROR "usage: cmake -DNM=<nm> -DLIBRARY=<file.so> -P CheckExportedSymbols.cmake")
endif()
include(${CMAKE_CURRENT_LIST_DIR}/../NmListing.cmake)
nm_lines(lines ${LIBRARY} -D --defined-only --demangle)
list(FILTER lines EXCLUDE REGEX "^[ \t]*$")
list(LENGTH lines exported)
set(internal ${lines})
list(FILTER internal INCLUDE REGEX "mvcl::detail::|mvcl::gltf::|tinygltf::|nlohmann::")
list(LENGTH internal internalCount)
message("${LIBRARY}: ${exported} exported symbols, ${internalCount} internal")
if(internalCount GREATER 0)
    list(SUBLIST internal 0 10 first)
    list(TRANSFORM first REPLACE "^[0-9a-fA-F]* *[A-Za-z] " "")
    list(JOIN first "\n  " first)
    # Printed as is (a FATAL_ERROR message is re-wrapped), then failed.
    message("${LIBRARY} exports ${internalCount} internal symbol(s):\n  ${first}\n")
    message(FATAL_ERROR "internal symbols are exported")
endif()
