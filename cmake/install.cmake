# `cmake --install`: the public header in include/tetprobe/, the shared libraries (with SONAME), a CMake
# package (find_package(tetprobe) -> tetprobe::tetprobe, tetprobe::runtime), pkg-config files and the
# command-line tool `tetprobe`.
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
# into any directory gives files that work there. Where that library folder is not one the system's
# loader searches, `--libs` also gives an RPATH to it, so a program built with it runs as it is (no
# LD_LIBRARY_PATH); which it is is known only at install time (--prefix), so the files are finished then.
set(TP_PC_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH TP_PC_TO_PREFIX /${TP_PC_DIR} /)
string(REGEX REPLACE "/$" "" TP_PC_TO_PREFIX "${TP_PC_TO_PREFIX}")
set(TP_PC_RPATH "@TP_PC_RPATH@")  # kept for the install step
foreach(library ${TP_INSTALLED_LIBRARIES})
  if(library STREQUAL "tetprobe")
    set(TP_PC_DESCRIPTION "Light probes on a tetrahedral tessellation: bake and run time")
  else()
    set(TP_PC_DESCRIPTION "Light probes on a tetrahedral tessellation: run time only (load, query)")
  endif()
  set(TP_PC_LIBRARY ${library})
  configure_file(${PROJECT_SOURCE_DIR}/cmake/tetprobe.pc.in ${PROJECT_BINARY_DIR}/pkgconfig/${library}.pc.in @ONLY)
endforeach()
if(WIN32)
  set(TP_PC_RPATH_FLAG "")
else()
  set(TP_PC_RPATH_FLAG " -Wl,-rpath,\\\${libdir}")
endif()
# The loader's own folders need no RPATH: the compiler's implicit link folders are those.
set(TP_PC_SYSTEM_LIBDIRS ${CMAKE_C_IMPLICIT_LINK_DIRECTORIES} /lib /usr/lib /lib64 /usr/lib64)
configure_file(${PROJECT_SOURCE_DIR}/cmake/install_pkgconfig.cmake.in ${PROJECT_BINARY_DIR}/install_pkgconfig.cmake @ONLY)
install(SCRIPT ${PROJECT_BINARY_DIR}/install_pkgconfig.cmake)

# The command-line tool `tetprobe` in bin/, with an RPATH to the installed libraries relative to itself, so it
# runs from any prefix as it is.
if(TARGET tetprobe_cli)
  file(RELATIVE_PATH TP_BIN_TO_LIB /${CMAKE_INSTALL_BINDIR} /${CMAKE_INSTALL_LIBDIR})
  set_target_properties(tetprobe_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${TP_BIN_TO_LIB}")
  install(TARGETS tetprobe_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
