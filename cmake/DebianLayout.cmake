# Run by cpack (CPACK_PRE_BUILD_SCRIPTS, cmake/ArchipelagoPackage.cmake) on its staging tree of `cmake --install`
# under /usr, before it packs the .deb: what Debian's policy adds to that tree.
#   * the Python module moves to lib/python3/dist-packages, where Debian's python3 finds it (a prefix of /usr/local,
#     the default when the build tree was configured, chose lib/python3.X/dist-packages: docs/install.md);
#   * manual pages compressed (gzip -9n: no name or time stamp, so that the package is reproducible);
#   * share/doc/archipelago/copyright (resources/debian/copyright) and changelog.gz, one entry for this version,
#     dated by the last commit (SOURCE_DATE_EPOCH when set), so that two builds of one commit are the same.

file(GLOB_RECURSE _bins LIST_DIRECTORIES true "${CPACK_TEMPORARY_INSTALL_DIRECTORY}/*/bin")
set(_usr "")
foreach(_bin IN LISTS _bins)
  if(IS_DIRECTORY "${_bin}" AND _bin MATCHES "/usr/bin$")
    get_filename_component(_usr "${_bin}" DIRECTORY)
    break()
  endif()
endforeach()
if(NOT _usr)
  file(GLOB _top "${CPACK_TEMPORARY_INSTALL_DIRECTORY}/*")
  message(FATAL_ERROR "DebianLayout: no usr/bin under ${CPACK_TEMPORARY_INSTALL_DIRECTORY} (${_top})")
endif()

# The Python module.
set(_debian_python lib/python3/dist-packages)
if(CPACK_ARCHIPELAGO_PYTHON_DIR AND NOT CPACK_ARCHIPELAGO_PYTHON_DIR STREQUAL _debian_python)
  set(_from "${_usr}/${CPACK_ARCHIPELAGO_PYTHON_DIR}/archipelago")
  if(NOT IS_DIRECTORY "${_from}")
    message(FATAL_ERROR "DebianLayout: no Python module in ${_from}")
  endif()
  file(MAKE_DIRECTORY "${_usr}/${_debian_python}")
  file(RENAME "${_from}" "${_usr}/${_debian_python}/archipelago")
  # The folders left empty (lib/python3.11/dist-packages, lib/python3.11).
  set(_dir "${_usr}/${CPACK_ARCHIPELAGO_PYTHON_DIR}")
  while(NOT _dir STREQUAL _usr)
    file(GLOB _left "${_dir}/*")
    if(_left)
      break()
    endif()
    file(REMOVE_RECURSE "${_dir}")
    get_filename_component(_dir "${_dir}" DIRECTORY)
  endwhile()
endif()

find_program(_gzip gzip REQUIRED)
file(GLOB _pages "${_usr}/share/man/man1/*.1")
foreach(_page IN LISTS _pages)
  execute_process(COMMAND ${_gzip} -9nf "${_page}" RESULT_VARIABLE _bad)
  if(_bad)
    message(FATAL_ERROR "DebianLayout: gzip -9n ${_page} failed")
  endif()
endforeach()

set(_doc "${_usr}/share/doc/${CPACK_PACKAGE_NAME}")
file(MAKE_DIRECTORY "${_doc}")
file(COPY_FILE "${CPACK_ARCHIPELAGO_SOURCE_DIR}/resources/debian/copyright" "${_doc}/copyright")
if(DEFINED ENV{SOURCE_DATE_EPOCH})
  set(_epoch "$ENV{SOURCE_DATE_EPOCH}")
else()
  execute_process(COMMAND git -C "${CPACK_ARCHIPELAGO_SOURCE_DIR}" log -1 --format=%ct
    OUTPUT_VARIABLE _epoch OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE _bad)
  if(_bad OR NOT _epoch)
    string(TIMESTAMP _epoch "%s" UTC)
  endif()
endif()
set(ENV{SOURCE_DATE_EPOCH} "${_epoch}")  # string(TIMESTAMP) formats that time
string(TIMESTAMP _date "%a, %d %b %Y %H:%M:%S +0000" UTC)
file(WRITE "${_doc}/changelog" "${CPACK_PACKAGE_NAME} (${CPACK_PACKAGE_VERSION}) unstable; urgency=medium

  * Archipelago ${CPACK_PACKAGE_VERSION}, packaged from its source tree by CPack (docs/install.md).

 -- ${CPACK_DEBIAN_PACKAGE_MAINTAINER}  ${_date}
")
execute_process(COMMAND ${_gzip} -9nf "${_doc}/changelog" RESULT_VARIABLE _bad)
if(_bad)
  message(FATAL_ERROR "DebianLayout: gzip -9n ${_doc}/changelog failed")
endif()
