# `cmake --install BUILD --prefix PREFIX` and CPack (docs/building.md, "Installing"). Installs
# the public headers of engine, oracle and io (their include/ folders, nothing of src/), the
# three static libraries with the CMake package pgeConfig.cmake (targets pge::engine, pge::oracle,
# pge::io), and the pge command. Two components, which CPack makes into two Debian packages:
#   runtime      the pge command                          -> pge_VERSION_ARCH.deb
#   development  headers, libraries, the CMake package    -> libpge-dev_VERSION_ARCH.deb
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PGE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/pge)

foreach(part engine oracle io)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${part}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          COMPONENT development FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(TARGETS pge_engine pge_oracle pge_io EXPORT pgeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT pgeTargets NAMESPACE pge:: DESTINATION ${PGE_CMAKE_DIR} COMPONENT development)

# pgeConfig.cmake asks a consumer for the minimum versions the top-level CMakeLists.txt asks for
# (PGE_BOOST_MIN, PGE_NLOHMANN_JSON_MIN, PGE_CGAL_MIN).
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/pgeConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/pgeConfig.cmake INSTALL_DESTINATION ${PGE_CMAKE_DIR})
# 0.x: a minor version may break the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pgeConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pgeConfig.cmake ${PROJECT_BINARY_DIR}/pgeConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/pgeGmp.cmake
        DESTINATION ${PGE_CMAKE_DIR} COMPONENT development)

install(TARGETS pge RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)

# CPack: `cpack -G DEB` in the build folder writes both packages (scripts/check-install.sh --deb
# checks them).
set(CPACK_PACKAGE_NAME pge)
set(CPACK_PACKAGE_VENDOR "PGE")
set(CPACK_PACKAGE_CONTACT "PGE maintainers <pge@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "event-driven 2D physics engine with an exact-oracle verification harness")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime development)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME pge)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION science)
# The command's shared libraries (libstdc++, GMP, fmt, Box2D, Chipmunk, ...) are read off the
# binary by dpkg-shlibdeps; gnuplot draws pge report's plots.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "gnuplot-nox")
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION
    "event-driven 2D physics engine: the pge command\n run, check, fuzz, report, gate, render and compare scenes; every event judged by an exact oracle.")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME libpge-dev)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SECTION libdevel)
# Static libraries: a consumer compiles against these headers and links these libraries
# (libgcc-12-dev: quadmath.h and libquadmath for pge::Quad, GCC's __float128).
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS
    "libboost-dev (>= ${PGE_BOOST_MIN}), libgcc-12-dev, libgmp-dev, libmpfr-dev, libcgal-dev (>= ${PGE_CGAL_MIN}), libflint-arb-dev, libfmt-dev, nlohmann-json3-dev (>= ${PGE_NLOHMANN_JSON_MIN})")
set(CPACK_DEBIAN_DEVELOPMENT_DESCRIPTION
    "event-driven 2D physics engine: headers, static libraries and CMake package\n pge::engine, pge::oracle (the exact referee) and pge::io (scene files) for find_package(pge).")
include(CPack)
