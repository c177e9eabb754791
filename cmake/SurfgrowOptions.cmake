# One place for the compile options every surfgrow target shares.

include(GNUInstallDirs)

set(SURFGROW_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align
    -Wunused -Woverloaded-virtual -Wnull-dereference -Wformat=2 -Wimplicit-fallthrough)
# GCC's -Wdouble-promotion flags float arithmetic silently carried out in double (a slow path and
# a result that differs from the float kernels'); clang's also flags every exact float-to-double
# assignment, which is how float results reach the double API. GCC's meaning on both.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    list(APPEND SURFGROW_WARNINGS -Wdouble-promotion)
endif()

# Floating point as written: no fused multiply-adds the compiler picks per target, so a build for
# any CPU gives the same bytes (docs/performance.md, "Portable binaries").
add_compile_options(-ffp-contract=off)

# Global, not per target: headers with SIMD code must see the same flags in every unit.
if(SURFGROW_NATIVE)
    add_compile_options(-march=native)
endif()

# -O1 -g1 whatever the build type: GCC's UBSan at -O2 -g compiles 4-8x slower than a Release unit
# (a test file: 121 s against 16 s; -O1 -g1: 63 s), and -O1 with line tables is what ASan's own
# documentation suggests: exact reports, file:line in every stack, tests still fast.
if(SURFGROW_SANITIZE)
    add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
                        -fno-sanitize-recover=undefined -O1 -g1)
    add_link_options(-fsanitize=address,undefined)
endif()

# libFuzzer: every unit carries the fuzzer's coverage hooks and ASan+UBSan (UB aborts, so the
# fuzzer sees it); only fuzz/'s targets link the fuzzer's main (-fsanitize=fuzzer).
if(SURFGROW_BUILD_FUZZERS)
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
        message(FATAL_ERROR "SURFGROW_BUILD_FUZZERS needs clang (libFuzzer): "
                            "-DCMAKE_CXX_COMPILER=clang++ (scripts/fuzz.sh does this)")
    endif()
    add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                        -fno-sanitize-recover=undefined)
    add_link_options(-fsanitize=address,undefined)
endif()

# Apply warnings (and -Werror in CI) to one of our own targets.
function(surfgrow_target_options target)
    target_compile_options(${target} PRIVATE ${SURFGROW_WARNINGS})
    if(SURFGROW_WERROR)
        target_compile_options(${target} PRIVATE -Werror)
    endif()
endfunction()

# Declare one of surfgrow's libraries: the alias surfgrow::<part> (what users link), includes that
# work from the build tree and from an installed one, and a place in the installed package.
set_property(GLOBAL PROPERTY SURFGROW_LIBRARIES "")
function(surfgrow_library target part)
    add_library(surfgrow::${part} ALIAS ${target})
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${part})
    target_include_directories(${target} PUBLIC
        $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>
        $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_compile_features(${target} PUBLIC cxx_std_20)
    surfgrow_target_options(${target})
    set_property(GLOBAL APPEND PROPERTY SURFGROW_LIBRARIES ${target})
endfunction()
