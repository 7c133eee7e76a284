# Fails when code compiled for one instruction set could run in place of another's: the tracer's
# kernel units (framework/src/tracer/*Avx2.cpp, *Avx512.cpp, compiled with -mavx2 / -mavx512f) must
# define no weak function that an object of another instruction set defines too (the linker keeps
# one copy of a weak symbol, any one, so a baseline caller could end up in AVX2 code), and must
# run nothing at start-up (that would run before the CPU is checked). See
# framework/src/tracer/KernelIsa.h.
#
#   cmake -DNM=<nm> "-DOBJECTS=<object>|<object>|..." -P CheckIsaSymbols.cmake
#
# An object's instruction set is read from its name: ...Avx2.cpp.o, ...Avx512.cpp.o, and baseline
# for every other. Prints "<n> objects, <k> kernel objects: <w> weak functions in kernel objects,
# <s> shared with another instruction set, <i> with start-up code" and, when s or i is not 0,
# the symbols and objects.
cmake_minimum_required(VERSION 3.25)
if(NOT NM OR NOT OBJECTS)
    message(FATAL_ERROR "usage: cmake -DNM=<nm> \"-DOBJECTS=<object>|<object>|...\" -P CheckIsaSymbols.cmake")
endif()
string(REPLACE "|" ";" objects "${OBJECTS}")
include(${CMAKE_CURRENT_LIST_DIR}/../NmListing.cmake)

# Weak definitions of code, as nm prints them: W. Weak data (V: typeinfo, vtables, a function's
# static variables) does not depend on the instruction set; a vtable's functions are checked as
# functions.
set(weak_regex "^[0-9a-fA-F]* +W ([^ ]+)$")
set(startup_regex "_GLOBAL__sub_I_|_GLOBAL__I_|__cxx_global_var_init")

function(weak_symbols object out_var)
    nm_lines(lines ${object} --defined-only)
    set(weak)
    set(startup)
    foreach(line IN LISTS lines)
        if(line MATCHES "${weak_regex}")
            list(APPEND weak "${CMAKE_MATCH_1}")
        elseif(line MATCHES "${startup_regex}")
            list(APPEND startup "${line}")
        endif()
    endforeach()
    set(${out_var} "${weak}" PARENT_SCOPE)
    set(${out_var}_startup "${startup}" PARENT_SCOPE)
endfunction()

set(isas baseline avx2 avx512)
foreach(isa IN LISTS isas)
    set(weak_${isa})
endforeach()
set(kernel_objects 0)
set(startup_objects)
list(LENGTH objects object_count)
foreach(object IN LISTS objects)
    if(object MATCHES "Avx512\\.[a-z+]*\\.o(bj)?$")
        set(isa avx512)
    elseif(object MATCHES "Avx2\\.[a-z+]*\\.o(bj)?$")
        set(isa avx2)
    else()
        set(isa baseline)
    endif()
    weak_symbols(${object} weak)
    list(APPEND weak_${isa} ${weak})
    if(NOT isa STREQUAL "baseline")
        math(EXPR kernel_objects "${kernel_objects} + 1")
        list(APPEND kernel_weak_${isa} ${weak})
        if(weak_startup)
            list(APPEND startup_objects ${object})
        endif()
    endif()
endforeach()
foreach(isa IN LISTS isas)
    list(REMOVE_DUPLICATES weak_${isa})
endforeach()

# A kernel object's weak function is shared when an object of another instruction set defines it.
set(kernel_weak_count 0)
set(shared)
foreach(isa avx2 avx512)
    if(NOT kernel_weak_${isa})
        continue()
    endif()
    list(REMOVE_DUPLICATES kernel_weak_${isa})
    list(LENGTH kernel_weak_${isa} n)
    math(EXPR kernel_weak_count "${kernel_weak_count} + ${n}")
    foreach(symbol IN LISTS kernel_weak_${isa})
        foreach(other IN LISTS isas)
            if(other STREQUAL isa)
                continue()
            endif()
            list(FIND weak_${other} "${symbol}" at)
            if(at GREATER -1)
                list(APPEND shared "${symbol} (${isa} and ${other})")
            endif()
        endforeach()
    endforeach()
endforeach()
list(LENGTH shared shared_count)
list(LENGTH startup_objects startup_count)
message("${object_count} objects, ${kernel_objects} kernel objects: ${kernel_weak_count} weak functions in kernel "
        "objects, ${shared_count} shared with another instruction set, ${startup_count} with start-up code")
if(shared_count GREATER 0 OR startup_count GREATER 0)
    set(report "")
    foreach(entry IN LISTS shared)
        # Demangled for the reader; the comparison above is on the mangled names.
        string(REGEX MATCH "^[^ ]+" mangled "${entry}")
        string(REGEX MATCH "\\([^)]*\\)$" isas_of "${entry}")
        execute_process(COMMAND c++filt ${mangled} OUTPUT_VARIABLE readable OUTPUT_STRIP_TRAILING_WHITESPACE
                        RESULT_VARIABLE filt_status)
        if(NOT filt_status EQUAL 0 OR NOT readable)
            set(readable ${mangled})
        endif()
        string(APPEND report "  shared: ${readable} ${isas_of}\n")
    endforeach()
    foreach(object IN LISTS startup_objects)
        string(APPEND report "  start-up code: ${object}\n")
    endforeach()
    # Printed as is (a FATAL_ERROR message is re-wrapped), then failed.
    message("${report}")
    message(FATAL_ERROR "kernel objects share code with another instruction set or run at start-up")
endif()
