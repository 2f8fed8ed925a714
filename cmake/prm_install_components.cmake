# Installing the libraries of a full build beside the codec (codec/prm_install.cmake): prm::common, prm::remesh,
# prm::pipeline, prm::gltf, each with its public headers, its own export file (prm-<c>-targets.cmake) and a loader
# (prm-<c>.cmake) that finds the packages its interface needs; prmConfig.cmake loads them as components.
# Included by the top-level CMakeLists.txt after the libraries' folders. The command-line tool is installed there too.
include(GNUInstallDirs)

# Packages each library needs from its user: those of its public interface always; a static library also needs
# its private ones, which end up linked into the program (prm_tinygltf is folded into prm_common, and tinygltf,
# like OpenMesh, is never reached from an installed header).
set(prm_common_public Threads)
set(prm_common_private TBB tinyobjloader)
set(prm_remesh_public "")
set(prm_remesh_private OpenMesh TBB)
set(prm_pipeline_public "")
set(prm_pipeline_private "")
set(prm_gltf_public nlohmann_json)
set(prm_gltf_private draco meshoptimizer)

foreach(c common remesh pipeline gltf)
  set(lib prm_${c})
  add_library(prm::${c} ALIAS ${lib})
  # INSTALL_RPATH: a shared library finds the ones it builds on beside it (a program's RUNPATH serves only the
  # libraries it links itself, and the linker may drop e.g. libprm_pipeline from a program that calls prm_gltf only).
  set_target_properties(${lib} PROPERTIES EXPORT_NAME ${c} INSTALL_RPATH "$ORIGIN"
    VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
  install(TARGETS ${lib} EXPORT prm-${c}-targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT prm-${c}-targets NAMESPACE prm:: DESTINATION ${PRM_INSTALL_CMAKEDIR})

  set(PRM_COMPONENT ${c})
  set(PRM_COMPONENT_DEPENDENCIES ${prm_${c}_public})
  get_target_property(type ${lib} TYPE)
  if(type STREQUAL "STATIC_LIBRARY")
    list(APPEND PRM_COMPONENT_DEPENDENCIES ${prm_${c}_private})
    list(REMOVE_DUPLICATES PRM_COMPONENT_DEPENDENCIES)
    set(PRM_COMPONENT_LINKAGE "a static")
    set(PRM_COMPONENT_DEPENDENCIES_NOTE "those of its interface and those it links privately")
  else()
    set(PRM_COMPONENT_LINKAGE "a shared")
    set(PRM_COMPONENT_DEPENDENCIES_NOTE "those of its interface only")
  endif()
  string(REPLACE ";" " " PRM_COMPONENT_DEPENDENCIES "${PRM_COMPONENT_DEPENDENCIES}")
  configure_file(${CMAKE_CURRENT_LIST_DIR}/prm-component.cmake.in "${PROJECT_BINARY_DIR}/prm-${c}.cmake" @ONLY)
  install(FILES "${PROJECT_BINARY_DIR}/prm-${c}.cmake" DESTINATION ${PRM_INSTALL_CMAKEDIR})
endforeach()

install(DIRECTORY common/include/ remesh/include/ pipeline/include/ gltf_ext/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")

# The command-line tool; with shared libraries it finds them beside it in the installed tree.
install(TARGETS prm RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(BUILD_SHARED_LIBS)
  file(RELATIVE_PATH rel "/prefix/${CMAKE_INSTALL_BINDIR}" "/prefix/${CMAKE_INSTALL_LIBDIR}")
  set_target_properties(prm PROPERTIES INSTALL_RPATH "$ORIGIN/${rel}")
endif()
