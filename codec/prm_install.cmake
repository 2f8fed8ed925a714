# Installing the codec: libraries, public headers, CMake package (find_package(prm): prm::decoder, prm::codec),
# pkg-config files (prm.pc, prm-decoder.pc), the format spec and the licence. Included by codec/CMakeLists.txt.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PRM_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/prm" CACHE STRING "Where prmConfig.cmake is installed")

install(TARGETS prm_decoder prm_codec EXPORT prmTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES
    include/prm/codec.h include/prm/export.h include/prm/lattice.h include/prm/prm.h
    "${PROJECT_BINARY_DIR}/include/prm/version.h"
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/prm)
install(EXPORT prmTargets NAMESPACE prm:: DESTINATION ${PRM_INSTALL_CMAKEDIR})

configure_package_config_file(cmake/prmConfig.cmake.in "${PROJECT_BINARY_DIR}/prmConfig.cmake"
  INSTALL_DESTINATION ${PRM_INSTALL_CMAKEDIR})
# 0.x: a new minor version may break the API, so a request for 0.1 accepts 0.1.x only.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/prmConfigVersion.cmake"
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/prmConfig.cmake" "${PROJECT_BINARY_DIR}/prmConfigVersion.cmake"
  DESTINATION ${PRM_INSTALL_CMAKEDIR})

# pkg-config: paths relative to the .pc file, so that the installed tree can move (cmake --install --prefix).
file(RELATIVE_PATH PRM_PC_TO_PREFIX "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
string(REGEX REPLACE "/$" "" PRM_PC_TO_PREFIX "${PRM_PC_TO_PREFIX}")
if(BUILD_SHARED_LIBS)
  set(PRM_PC_LIBS_PRIVATE "")
  set(PRM_PC_CFLAGS "")
else()
  set(PRM_PC_LIBS_PRIVATE "Libs.private: -lstdc++ -lm")  # a static C++ library, linked from C
  set(PRM_PC_CFLAGS " -DPRM_STATIC_DEFINE")
endif()
foreach(pc prm prm-decoder)
  if(pc STREQUAL "prm")
    set(PRM_PC_LIB prm_codec)
    set(PRM_PC_DESCRIPTION "PRM mesh codec: encoder and decoder of piecewise regular mesh streams")
  else()
    set(PRM_PC_LIB prm_decoder)
    set(PRM_PC_DESCRIPTION "PRM mesh decoder: decodes piecewise regular mesh streams (no encoder)")
  endif()
  configure_file(cmake/prm.pc.in "${PROJECT_BINARY_DIR}/${pc}.pc" @ONLY)
  install(FILES "${PROJECT_BINARY_DIR}/${pc}.pc" DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endforeach()

install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" "${PROJECT_SOURCE_DIR}/spec/prm-format.md"
  DESTINATION ${CMAKE_INSTALL_DOCDIR})
