# One place for the compile options every surfgrow target shares.

set(SURFGROW_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align
    -Wunused -Woverloaded-virtual -Wnull-dereference -Wdouble-promotion -Wformat=2
    -Wimplicit-fallthrough)

# Global, not per target: headers with SIMD code must see the same flags in every unit.
if(SURFGROW_NATIVE)
    add_compile_options(-march=native)
endif()

if(SURFGROW_SANITIZE)
    add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
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
