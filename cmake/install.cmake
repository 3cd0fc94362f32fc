# `cmake --install`: the public header in include/tetprobe/, the shared libraries (with SONAME), a CMake
# package (find_package(tetprobe) -> tetprobe::tetprobe, tetprobe::runtime) and pkg-config files.
include(CMakePackageConfigHelpers)

set(TP_CMAKE_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/tetprobe)

install(FILES ${PROJECT_SOURCE_DIR}/capi/tetprobe.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tetprobe)
install(TARGETS ${TP_INSTALLED_LIBRARIES} EXPORT tetprobeTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT tetprobeTargets NAMESPACE tetprobe:: DESTINATION ${TP_CMAKE_PACKAGE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/tetprobeConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/tetprobeConfig.cmake INSTALL_DESTINATION ${TP_CMAKE_PACKAGE_DIR})
# 0.x: a minor release may change the ABI, so only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/tetprobeConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/tetprobeConfig.cmake ${PROJECT_BINARY_DIR}/tetprobeConfigVersion.cmake
        DESTINATION ${TP_CMAKE_PACKAGE_DIR})

# pkg-config files find the prefix from their own place (${pcfiledir}), so `cmake --install --prefix`
# into any directory gives files that work there.
set(TP_PC_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH TP_PC_TO_PREFIX /${TP_PC_DIR} /)
string(REGEX REPLACE "/$" "" TP_PC_TO_PREFIX "${TP_PC_TO_PREFIX}")
foreach(library ${TP_INSTALLED_LIBRARIES})
  if(library STREQUAL "tetprobe")
    set(TP_PC_DESCRIPTION "Light probes on a tetrahedral tessellation: bake and run time")
  else()
    set(TP_PC_DESCRIPTION "Light probes on a tetrahedral tessellation: run time only (load, query)")
  endif()
  set(TP_PC_LIBRARY ${library})
  configure_file(${PROJECT_SOURCE_DIR}/cmake/tetprobe.pc.in ${PROJECT_BINARY_DIR}/${library}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/${library}.pc DESTINATION ${TP_PC_DIR})
endforeach()
