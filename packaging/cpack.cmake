# Debian package (CPack DEB) of the pointnpr CLI and the MeshLab plugins; see docs/meshlab.md.
#
#   cmake --build build --target package        (or: cd build && cpack --config CPackConfig.cmake)
#
# gives build/pointnpr_<version>-1_<arch>.deb with
#   /usr/bin/pointnpr
#   /usr/lib/x86_64-linux-gnu/meshlab/plugins/libfilter_pointnpr.so   (install component meshlab)
#   /usr/lib/x86_64-linux-gnu/meshlab/plugins/libdecorate_pointnpr.so (when the renderer is built)
# Depends: meshlab (= the version installed at configure time: a plugin only works in the MeshLab
# it was compiled against), the shared libraries the binaries link (dpkg-shlibdeps) and the
# libraries the renderer loads at run time (libepoxy dlopens libEGL/libGL; Mesa's drivers).
# The static libraries and headers (the top level's install rules) are left out: this is a
# runtime package; `cmake --install build` still installs them.
# Included once from the top-level CMakeLists.txt, after the components' add_subdirectory().

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME pointnpr)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Non-photorealistic rendering of point clouds: pointnpr CLI and MeshLab 2020.09 plugins")
set(CPACK_PACKAGE_DESCRIPTION
    "pointnpr computes feature degrees, profile lines and segmentations of point clouds and renders\n\
them in non-photorealistic styles. This package holds the pointnpr command-line tool and, when\n\
built, the MeshLab filter plugin (Filters > Point Set > NPR: ...) and the decorator\n\
(Render > NPR render), built against the exact MeshLab version it depends on.")
set(PNPR_DEB_MAINTAINER "pointnpr developers <pointnpr@localhost>" CACHE STRING
    "Maintainer field of the .deb (placeholder address: set it for a real release)")
set(CPACK_PACKAGE_CONTACT "${PNPR_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${PNPR_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT) # pointnpr_<version>-<release>_<arch>.deb

# Stage with DESTDIR: the plugins are installed to an absolute folder (PNPR_MESHLAB_LIBDIR/plugins);
# without DESTDIR, CPack would copy them into the live system folder while packaging.
set(CPACK_SET_DESTDIR ON)
set(CPACK_INSTALL_PREFIX /usr)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# Runtime package: after the staging install, drop the static libraries and the headers.
set(CPACK_PRE_BUILD_SCRIPTS ${CMAKE_CURRENT_LIST_DIR}/cpack-prune.cmake)

# Dependencies. dpkg-shlibdeps (dpkg-dev) finds the packages of the linked libraries
# (libopenmesh1, libepoxy0, libpng16-16, Qt5, libopengl0...); libmeshlab-common.so lives in
# MeshLab's private folder, given as a private dir so that dpkg-shlibdeps can resolve it.
find_program(PNPR_DPKG_SHLIBDEPS dpkg-shlibdeps)
find_program(PNPR_DPKG_QUERY dpkg-query)
if(PNPR_DPKG_SHLIBDEPS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
  if(PNPR_MESHLAB_LIBDIR)
    set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PNPR_MESHLAB_LIBDIR})
  endif()
  set(_pnpr_deb_depends "")
else()
  message(WARNING "packaging: dpkg-shlibdeps (dpkg-dev) not found - the .deb lists explicit library dependencies only")
  set(_pnpr_deb_depends "libc6, libstdc++6, libopenmesh1, libpng16-16, libepoxy0")
endif()
# libepoxy dlopens libEGL/libGL, which load Mesa's drivers: no NEEDED entry shows them.
if(TARGET pointnpr_render)
  list(APPEND _pnpr_deb_depends "libegl1, libgl1, libgl1-mesa-dri")
endif()

# The exact MeshLab version the plugins were compiled against (its headers come from the source
# package of the installed version: scripts/meshlab-source.sh).
set(PNPR_DEB_MESHLAB_VERSION "" CACHE STRING
    "MeshLab package version the .deb depends on (=); empty = dpkg-query of the installed meshlab")
set(_pnpr_deb_meshlab "")
if(TARGET filter_pointnpr)
  set(_pnpr_deb_meshlab "${PNPR_DEB_MESHLAB_VERSION}")
  if(NOT _pnpr_deb_meshlab AND PNPR_DPKG_QUERY)
    execute_process(COMMAND ${PNPR_DPKG_QUERY} -W -f=\${Version} meshlab
                    OUTPUT_VARIABLE _pnpr_deb_meshlab ERROR_QUIET RESULT_VARIABLE _pnpr_rc)
    if(NOT _pnpr_rc EQUAL 0)
      set(_pnpr_deb_meshlab "")
    endif()
    string(STRIP "${_pnpr_deb_meshlab}" _pnpr_deb_meshlab)
  endif()
  if(_pnpr_deb_meshlab)
    list(PREPEND _pnpr_deb_depends "meshlab (= ${_pnpr_deb_meshlab})")
    message(STATUS "packaging: the .deb depends on meshlab (= ${_pnpr_deb_meshlab})")
  else()
    list(PREPEND _pnpr_deb_depends "meshlab")
    message(WARNING "packaging: meshlab's package version is unknown (no dpkg-query or no meshlab package): "
                    "the .deb depends on an unversioned meshlab; set -DPNPR_DEB_MESHLAB_VERSION=...")
  endif()
endif()
list(JOIN _pnpr_deb_depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
set(PNPR_DEB_MESHLAB_DEPENDS "${_pnpr_deb_meshlab}") # for the test below

include(CPack)

# Test: build the .deb, inspect it, extract it (never dpkg -i) and run meshlabserver with the
# extracted plugins (tests/meshlab/package.sh). Only where the plugins are built (not in the
# sanitizer/fuzz configuration) and the tools are there.
find_program(PNPR_DPKG_DEB dpkg-deb)
if(TARGET filter_pointnpr AND PNPR_DPKG_DEB AND PNPR_XVFB AND PNPR_MESHLABSERVER
   AND PNPR_DEB_MESHLAB_DEPENDS)
  set(_pnpr_deb_decorate "")
  if(TARGET decorate_pointnpr)
    set(_pnpr_deb_decorate libdecorate_pointnpr.so)
  endif()
  add_test(NAME meshlab_package
           COMMAND bash ${CMAKE_SOURCE_DIR}/tests/meshlab/package.sh ${CMAKE_CPACK_COMMAND} ${CMAKE_BINARY_DIR}/CPackConfig.cmake
                   ${CMAKE_BINARY_DIR}/meshlab-test/package "${PNPR_DEB_MESHLAB_DEPENDS}" ${PNPR_MESHLAB_LIBDIR}/plugins
                   ${_pnpr_deb_decorate})
  set_tests_properties(meshlab_package PROPERTIES TIMEOUT 300 LABELS meshlab)
endif()
