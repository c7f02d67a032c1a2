# CPACK_PRE_BUILD_SCRIPTS of packaging/cpack.cmake: runs after CPack's staging install, before the
# .deb is made. The .deb is a runtime package: remove the static libraries (libpointnpr*.a) and the
# headers (include/pointnpr) that the top level's install rules put under the prefix (/usr).
# Only these exact paths inside the staging folder are touched.
set(_root "${CPACK_TEMPORARY_INSTALL_DIRECTORY}")
if(NOT _root OR NOT _root MATCHES "/_CPack_Packages/" OR NOT IS_DIRECTORY "${_root}")
  message(FATAL_ERROR "cpack-prune: unexpected staging folder '${_root}'")
endif()
set(_prefix "${_root}${CPACK_PACKAGING_INSTALL_PREFIX}")
file(GLOB _static "${_prefix}/lib/libpointnpr*.a")
if(_static)
  file(REMOVE ${_static})
endif()
file(REMOVE_RECURSE "${_prefix}/include/pointnpr")
foreach(d "${_prefix}/include" "${_prefix}/lib")
  file(GLOB _left "${d}/*")
  if(IS_DIRECTORY "${d}" AND NOT _left)
    file(REMOVE_RECURSE "${d}") # empty
  endif()
endforeach()
message(STATUS "cpack-prune: removed the static libraries and headers from ${_prefix}")
