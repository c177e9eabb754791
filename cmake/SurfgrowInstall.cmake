# `cmake --install`: the libraries and their headers, the CMake package (find_package(surfgrow)),
# a pkg-config file, and the command line with its plot script.
include(CMakePackageConfigHelpers)

get_property(libraries GLOBAL PROPERTY SURFGROW_LIBRARIES)
install(TARGETS ${libraries} EXPORT surfgrowTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})

# Headers of the parts that were built; detail/ too, as public headers include some of it.
set(parts core planes robot pipeline scanner io eval)
if(SURFGROW_BUILD_RENDER)
    list(APPEND parts render)
endif()
if(SURFGROW_BUILD_VIEW)
    list(APPEND parts view)
endif()
foreach(part IN LISTS parts)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/surfgrow/${part}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/surfgrow FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(FILES ${PROJECT_BINARY_DIR}/include/surfgrow/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/surfgrow)

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/surfgrow)
install(EXPORT surfgrowTargets NAMESPACE surfgrow:: DESTINATION ${config_dir})
configure_package_config_file(cmake/surfgrowConfig.cmake.in
    ${PROJECT_BINARY_DIR}/surfgrowConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/surfgrowConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)  # 0.x: a minor version may change the API
install(FILES ${PROJECT_BINARY_DIR}/surfgrowConfig.cmake
              ${PROJECT_BINARY_DIR}/surfgrowConfigVersion.cmake DESTINATION ${config_dir})

# pkg-config: static libraries, so every library and what they link, in link order (each library
# is declared after those it uses, so the reverse of that order).
set(link_order ${libraries})
list(REVERSE link_order)
set(SURFGROW_PC_LIBS "")
foreach(lib IN LISTS link_order)
    string(APPEND SURFGROW_PC_LIBS " -l${lib}")
endforeach()
if(SURFGROW_BUILD_RENDER)
    string(APPEND SURFGROW_PC_LIBS " -lpng -lfreetype -lfontconfig")
endif()
string(STRIP "${SURFGROW_PC_LIBS}" SURFGROW_PC_LIBS)
configure_file(cmake/surfgrow.pc.in ${PROJECT_BINARY_DIR}/surfgrow.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/surfgrow.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/surfgrow)
if(SURFGROW_BUILD_CLI)
    install(TARGETS surfgrow RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    # The plot script `sweep` and `study` look for in <prefix>/share/surfgrow/plots.
    install(FILES ${PROJECT_SOURCE_DIR}/scripts/plots/surfgrow_plots.py
            DESTINATION ${CMAKE_INSTALL_DATADIR}/surfgrow/plots)
endif()
