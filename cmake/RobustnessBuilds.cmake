# Builds that check mvcl rather than ship it (docs/robustness.md, "Sanitizers and fuzzing" and
# "Build-flag invariance").
#
#   MVCL_SANITIZE=ON       every target with AddressSanitizer + UndefinedBehaviorSanitizer; the
#                          first report aborts the process, so a ctest run fails on any finding.
#                          GCC or clang. Used by scripts/ci-sanitizers.sh.
#   MVCL_SANITIZE_THREAD=ON  every target with ThreadSanitizer (clang); the first report fails
#                          the process. Needs a oneTBB built with -fsanitize=thread as well (point
#                          TBB_DIR at it): TSan cannot see the hand-offs inside an uninstrumented
#                          libtbb and reports every tile as a race. Used by scripts/ci-tsan.sh.
#   MVCL_BUILD_FUZZERS=ON  libFuzzer harnesses in tests/fuzz (clang only). The whole tree gets
#                          coverage instrumentation (-fsanitize=fuzzer-no-link) plus ASan/UBSan,
#                          so that libFuzzer sees the branches of the loader it is exploring.
#                          Used by scripts/ci-fuzz.sh.
#   MVCL_EXTRA_COMPILE_OPTIONS      options for every target, placed after mvcl's own so that
#                                   they win (-O0, -O3 -march=native, ...).
#   MVCL_FRAMEWORK_COMPILE_OPTIONS  options for the mvcl library only (its objects), likewise placed last:
#                                   -ffp-contract=fast there shows that the tracer's results do
#                                   not depend on FMA contraction, while the test programs that
#                                   generate the rays keep computing the same rays.
#                                   Both used by scripts/ci-flag-invariance.sh.
#
# Both options change flags for the whole tree, so use them in a build directory of their own.

option(MVCL_SANITIZE "Build with -fsanitize=address,undefined (abort on the first report)" OFF)
option(MVCL_SANITIZE_THREAD "Build with -fsanitize=thread (clang; with a oneTBB built the same way)" OFF)
option(MVCL_BUILD_FUZZERS "Build the libFuzzer harnesses in tests/fuzz (clang)" OFF)

if(MVCL_SANITIZE_THREAD)
    if(MVCL_SANITIZE OR MVCL_BUILD_FUZZERS)
        message(FATAL_ERROR "MVCL_SANITIZE_THREAD cannot be combined with AddressSanitizer (MVCL_SANITIZE, MVCL_BUILD_FUZZERS)")
    endif()
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
        message(FATAL_ERROR "MVCL_SANITIZE_THREAD needs clang; configure with -DCMAKE_CXX_COMPILER=clang++")
    endif()
    add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
    add_link_options(-fsanitize=thread)
endif()

if(MVCL_SANITIZE OR MVCL_BUILD_FUZZERS)
    # -fno-sanitize-recover: UBSan otherwise prints and carries on, and the test passes.
    # Frame pointers keep ASan's stack traces complete at -O1.
    set(MVCL_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
    add_compile_options(${MVCL_SANITIZER_FLAGS})
    add_link_options(-fsanitize=address,undefined)
endif()

if(MVCL_BUILD_FUZZERS)
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
        message(FATAL_ERROR "MVCL_BUILD_FUZZERS needs clang (libFuzzer); configure with -DCMAKE_CXX_COMPILER=clang++")
    endif()
    add_compile_options(-fsanitize=fuzzer-no-link)
    # Added here, before the framework: mvcl::mvcl is resolved when the build is generated, but an
    # imported target must exist when the subdirectory is created.
    find_package(TinyGLTF REQUIRED)
    add_subdirectory(${CMAKE_SOURCE_DIR}/tests/fuzz ${CMAKE_BINARY_DIR}/tests/fuzz)
endif()

set(MVCL_EXTRA_COMPILE_OPTIONS "" CACHE STRING "Compile options for every target, after mvcl's own (;-separated)")
set(MVCL_FRAMEWORK_COMPILE_OPTIONS "" CACHE STRING "Compile options for the mvcl library, after its own (;-separated)")
add_compile_options(${MVCL_EXTRA_COMPILE_OPTIONS})
if(MVCL_FRAMEWORK_COMPILE_OPTIONS)
    # Deferred to the end of the top-level CMakeLists.txt, when the mvcl target exists.
    cmake_language(DEFER CALL target_compile_options mvcl_objects PRIVATE ${MVCL_FRAMEWORK_COMPILE_OPTIONS})
endif()
