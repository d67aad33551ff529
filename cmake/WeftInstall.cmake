# `cmake --install build/<preset> --prefix DIR` makes DIR a CMake package that other projects use with
# find_package(weft) (docs/library.md):
#   DIR/lib/libweft_solver.a                             weft::solver (and weft::fp_policy, which weft::solver
#                                                        carries: the flags that keep every backend bitwise
#                                                        identical apply to callers' kernels too)
#   DIR/lib/libweft_io_{formats,hdf5,render}.a           weft::io_formats, weft::io_hdf5, weft::io_render, and
#                                                        weft::io, which links all three
#   DIR/include/weft/{core,scene,constraints,collision,solver,backends,io}/*.hpp, weft_version.hpp
#   DIR/lib/cmake/weft/weftConfig.cmake, weftConfigVersion.cmake, weftTargets*.cmake
include(CMakePackageConfigHelpers)
set(WEFT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/weft)

set(_weft_targets weft_solver weft_fp_policy)
set(WEFT_PACKAGE_HAS_IO FALSE)
if(TARGET weft_io)
  list(APPEND _weft_targets weft_io_formats weft_io_hdf5 weft_io_render weft_io)
  set(WEFT_PACKAGE_HAS_IO TRUE)
endif()
install(TARGETS ${_weft_targets} EXPORT weftTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT weftTargets NAMESPACE weft:: DESTINATION ${WEFT_INSTALL_CMAKEDIR})

# Headers keep their folders under include/weft/. io/usd/ is the private interface of the USD module.
install(DIRECTORY core scene constraints collision solver backends io DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/weft
        FILES_MATCHING PATTERN "*.hpp" PATTERN "usd" EXCLUDE)
install(FILES ${PROJECT_BINARY_DIR}/weft_version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/weft)

# The config file checks that the Kokkos it finds has the backends weft was compiled for.
set(WEFT_PACKAGE_KOKKOS_DEVICES "")
foreach(b IN LISTS WEFT_BACKENDS)
  string(TOUPPER ${b} dev)
  list(APPEND WEFT_PACKAGE_KOKKOS_DEVICES ${dev})
endforeach()
configure_package_config_file(cmake/weftConfig.cmake.in ${PROJECT_BINARY_DIR}/weftConfig.cmake
                              INSTALL_DESTINATION ${WEFT_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/weftConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/weftConfig.cmake ${PROJECT_BINARY_DIR}/weftConfigVersion.cmake
        DESTINATION ${WEFT_INSTALL_CMAKEDIR})
