# Fails when a per-instruction-set kernel object defines a symbol the linker could share with
# other objects (weak or unique: an inline function compiled with AVX that a baseline caller might
# be linked to). Run in script mode: cmake -DNM=<nm> -DOBJECTS=<a.o;b.o> -P check_kernel_symbols.cmake
cmake_minimum_required(VERSION 3.25)
foreach(object IN LISTS OBJECTS)
    execute_process(COMMAND ${NM} --defined-only ${object} OUTPUT_VARIABLE symbols
                    RESULT_VARIABLE failed)
    if(failed)
        message(FATAL_ERROR "${NM} failed on ${object}")
    endif()
    string(REPLACE "\n" ";" lines "${symbols}")
    foreach(line IN LISTS lines)
        # Weak (W, V), unique (u) or indirect (i) definitions, but for the personality routine's
        # reference that every object with unwind tables carries.
        if(line MATCHES " [WVui] " AND NOT line MATCHES "DW\\.ref\\.__gxx_personality_v0$")
            message(FATAL_ERROR "${object} shares a symbol with other objects: ${line}")
        endif()
    endforeach()
    message(STATUS "${object}: no shared symbols")
endforeach()
