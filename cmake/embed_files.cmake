# Build-time embedding: writes a C++ source that holds the bytes of some files, each behind a
# function returning a std::string_view. Run in script mode:
#   cmake -DOUTPUT=<file.cpp> -DNAMESPACE=<ns> -DITEMS=<name=path|name=path...> -P embed_files.cmake
# Files that go inside an inline <script> or <style> (every name but *_template) must not contain
# "</script" or "</style": a build error says so, rather than a page that breaks in the browser.
cmake_minimum_required(VERSION 3.25)

set(text "// Generated at build time by cmake/embed_files.cmake. Do not edit.\n")
string(APPEND text "#include <string_view>\n\nnamespace ${NAMESPACE} {\n\nnamespace {\n")
set(functions "")
string(REPLACE "|" ";" items "${ITEMS}")
foreach(item IN LISTS items)
    string(FIND "${item}" "=" eq)
    string(SUBSTRING "${item}" 0 ${eq} name)
    math(EXPR start "${eq} + 1")
    string(SUBSTRING "${item}" ${start} -1 path)
    if(NOT EXISTS "${path}")
        message(FATAL_ERROR "embed_files: ${path} does not exist")
    endif()
    file(READ "${path}" content)
    string(TOLOWER "${content}" lower)
    set(closers "</script" "</style")
    if(name MATCHES "_template$")
        set(closers "")
    endif()
    foreach(bad IN LISTS closers)
        string(FIND "${lower}" "${bad}" at)
        if(NOT at EQUAL -1)
            message(FATAL_ERROR "embed_files: ${path} contains '${bad}', which would end its inline block")
        endif()
    endforeach()
    file(READ "${path}" hex HEX)
    # 0xNN, per byte, 16 to a line; a trailing 0 keeps empty files valid (and is not counted).
    string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
    string(REPEAT "0x..," 16 line)
    string(REGEX REPLACE "(${line})"
           "\\1\n" bytes "${bytes}")
    string(APPEND text "// ${path}\nconstexpr unsigned char k_${name}[] = {\n${bytes}0};\n")
    string(APPEND functions "std::string_view ${name}() {\n"
           "    return {reinterpret_cast<const char*>(k_${name}), sizeof k_${name} - 1};\n}\n")
endforeach()
string(APPEND text "\n}  // namespace\n\n${functions}\n}  // namespace ${NAMESPACE}\n")
file(WRITE "${OUTPUT}.tmp" "${text}")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
