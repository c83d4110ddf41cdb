# Chooses the Qt major version from the Qwt that is available, and defines Qwt::Qwt, QT_LIB (Qt5 or Qt6) and
# ARCHIPELAGO_QWT_INCLUDE_DIRS.
#
#  * Qt 6 when a Qwt >= 6.2 built for Qt 6 is found (its library must link libQt6Widgets), looking in order at
#      1. -DQWT_ROOT=<prefix>: include/qwt_global.h (or include/qwt, include/qt6/qwt) and lib/libqwt*;
#         a QWT_ROOT that holds no such Qwt is an error;
#      2. a packaged one: libqwt-qt6 with headers in <include>/qwt (libqwt-qt6-dev, in Debian sid);
#      3. the prefix that scripts/build-qwt-qt6.sh built and checked last:
#         ${ARCHIPELAGO_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/archipelago}/qwt-qt6-current.
#  * Otherwise Qt 5.15 with Debian's libqwt-qt5-dev (headers in /usr/include/qwt, library libqwt-qt5).
# A Qwt for Qt 6 that is not packaged (1 or 3) is private to Archipelago: copied into <build>/lib/archipelago,
# linked from there, and installed into <prefix>/lib/archipelago (ARCHIPELAGO_PRIVATE_QWT_FILES; issue 36 class 9).
# -DARCHIPELAGO_QT_MAJOR=5|6 forces a choice, and configuring fails when the forced Qt or its Qwt is missing.
# The configure log names the Qt and Qwt versions and where the Qwt came from.

set(ARCHIPELAGO_QT_MAJOR "" CACHE STRING "Force the Qt major version (5 or 6); empty = Qt 6 when a Qwt for Qt 6 is found")
set_property(CACHE ARCHIPELAGO_QT_MAJOR PROPERTY STRINGS "" 5 6)
set(QWT_ROOT "" CACHE PATH "Prefix of a Qwt >= 6.2 built for Qt 6 (optional)")
if(NOT ARCHIPELAGO_QT_MAJOR MATCHES "^(5|6)?$")
  message(FATAL_ERROR "ARCHIPELAGO_QT_MAJOR must be 5, 6 or empty, not '${ARCHIPELAGO_QT_MAJOR}'")
endif()

# The version in a qwt_global.h, or "" when there is none.
function(_archipelago_qwt_header_version dir out)
  set(_v "")
  if(EXISTS "${dir}/qwt_global.h")
    file(STRINGS "${dir}/qwt_global.h" _line REGEX "define[ \t]+QWT_VERSION_STR")
    string(REGEX MATCH "\"[0-9.]+\"" _v "${_line}")
    string(REPLACE "\"" "" _v "${_v}")
  endif()
  set(${out} "${_v}" PARENT_SCOPE)
endfunction()

# Looks for a Qwt >= 6.2 < 7 for Qt 6 (headers and library given by the hints, or in the system paths when
# both are empty).  Sets _qwt6_include and _qwt6_library on success; _qwt6_why says why not otherwise.
# Results are not cached (NO_CACHE), so that a new QWT_ROOT or a rebuilt prefix is seen at once.
function(_archipelago_find_qwt6 label include_hints library_hints)
  set(_qwt6_include "" PARENT_SCOPE)
  set(_qwt6_library "" PARENT_SCOPE)
  if(include_hints)
    find_path(_inc qwt_global.h PATHS ${include_hints} NO_DEFAULT_PATH NO_CACHE)
    find_library(_lib NAMES qwt qwt-qt6 PATHS ${library_hints} NO_DEFAULT_PATH NO_CACHE)
  else()
    find_library(_lib NAMES qwt-qt6 NO_CACHE)
    find_path(_inc qwt_global.h PATH_SUFFIXES qwt qt6/qwt NO_CACHE)
  endif()
  if(NOT _lib)
    if(include_hints)
      set(_qwt6_why "${label}: no lib/libqwt.so" PARENT_SCOPE)
    else()
      set(_qwt6_why "${label}: no libqwt-qt6.so" PARENT_SCOPE)
    endif()
    return()
  endif()
  if(NOT _inc)
    set(_qwt6_why "${label}: ${_lib} but no qwt_global.h" PARENT_SCOPE)
    return()
  endif()
  _archipelago_qwt_header_version("${_inc}" _v)
  if(NOT _v VERSION_GREATER_EQUAL 6.2 OR NOT _v VERSION_LESS 7)
    set(_qwt6_why "${label}: ${_inc}/qwt_global.h is Qwt '${_v}', not >= 6.2 and < 7" PARENT_SCOPE)
    return()
  endif()
  file(STRINGS "${_lib}" _needed REGEX "libQt[0-9]Widgets\\.so" LIMIT_COUNT 1)
  if(NOT _needed MATCHES "libQt6Widgets")
    set(_qwt6_why "${label}: ${_lib} does not link libQt6Widgets (${_needed})" PARENT_SCOPE)
    return()
  endif()
  set(_qwt6_include "${_inc}" PARENT_SCOPE)
  set(_qwt6_library "${_lib}" PARENT_SCOPE)
  set(_qwt6_why "" PARENT_SCOPE)
endfunction()

# A private Qwt: copies `library` (libqwt.so), the links to its SONAME and the file they name into
# <build>/lib/archipelago; sets _qwt6_library to the copy (so that the build tree's run path names that folder)
# and ARCHIPELAGO_PRIVATE_QWT_FILES to the SONAME link and its file (what `cmake --install` installs).
set(ARCHIPELAGO_PRIVATE_QWT_FILES "")
set(ARCHIPELAGO_PRIVATE_LIBDIR lib/archipelago)  # relative to the prefix, and to the build tree
function(_archipelago_private_qwt library)
  find_program(ARCHIPELAGO_READELF NAMES readelf REQUIRED)
  execute_process(COMMAND ${ARCHIPELAGO_READELF} -d "${library}" OUTPUT_VARIABLE _dynamic RESULT_VARIABLE _bad)
  string(REGEX MATCH "Library soname: \\[([^]]+)\\]" _match "${_dynamic}")
  set(_soname "${CMAKE_MATCH_1}")
  if(_bad OR NOT _soname)
    message(FATAL_ERROR "${library}: no SONAME in readelf -d (${_bad})")
  endif()
  get_filename_component(_dir "${library}" DIRECTORY)
  get_filename_component(_real "${library}" REALPATH)
  get_filename_component(_real_name "${_real}" NAME)
  set(_to "${CMAKE_BINARY_DIR}/${ARCHIPELAGO_PRIVATE_LIBDIR}")
  file(MAKE_DIRECTORY "${_to}")
  file(COPY "${library}" "${_dir}/${_soname}" DESTINATION "${_to}" FOLLOW_SYMLINK_CHAIN)
  get_filename_component(_name "${library}" NAME)
  set(_qwt6_library "${_to}/${_name}" PARENT_SCOPE)
  set(_files "${_to}/${_soname}")
  if(NOT _real_name STREQUAL _soname)
    list(APPEND _files "${_to}/${_real_name}")
  endif()
  set(ARCHIPELAGO_PRIVATE_QWT_FILES "${_files}" PARENT_SCOPE)
endfunction()

set(_qt_major "${ARCHIPELAGO_QT_MAJOR}")
set(_qwt_source "")
set(_not_found "")

if(NOT _qt_major STREQUAL "5")
  if(QWT_ROOT)
    _archipelago_find_qwt6("QWT_ROOT=${QWT_ROOT}"
      "${QWT_ROOT}/include;${QWT_ROOT}/include/qwt;${QWT_ROOT}/include/qt6/qwt" "${QWT_ROOT}/lib;${QWT_ROOT}/lib64")
    if(NOT _qwt6_library)
      message(FATAL_ERROR "No Qwt for Qt 6 under -DQWT_ROOT: ${_qwt6_why}")
    endif()
    set(_qwt_source "QWT_ROOT")
  else()
    _archipelago_find_qwt6("packaged libqwt-qt6" "" "")
    if(_qwt6_library)
      set(_qwt_source "packaged")
    else()
      list(APPEND _not_found "${_qwt6_why}")
      if(DEFINED ENV{ARCHIPELAGO_CACHE})
        set(_cache "$ENV{ARCHIPELAGO_CACHE}")
      elseif(DEFINED ENV{XDG_CACHE_HOME})
        set(_cache "$ENV{XDG_CACHE_HOME}/archipelago")
      else()
        set(_cache "$ENV{HOME}/.cache/archipelago")
      endif()
      set(_built "${_cache}/qwt-qt6-current")
      if(EXISTS "${_built}/.archipelago-qwt-ok")
        get_filename_component(_built "${_built}" REALPATH)
        _archipelago_find_qwt6("${_built}" "${_built}/include" "${_built}/lib")
        if(_qwt6_library)
          set(_qwt_source "built by scripts/build-qwt-qt6.sh")
        else()
          list(APPEND _not_found "${_qwt6_why}")
        endif()
      else()
        list(APPEND _not_found "${_built}: not built (bash scripts/install-deps.sh builds it)")
      endif()
    endif()
  endif()

  if(_qwt6_library)
    if(_qt_major STREQUAL "6")
      find_package(Qt6 6.2 REQUIRED COMPONENTS Core Gui Widgets Svg SvgWidgets PrintSupport Concurrent Test)
    else()
      find_package(Qt6 6.2 QUIET COMPONENTS Core Gui Widgets Svg SvgWidgets PrintSupport Concurrent Test)
    endif()
    if(Qt6_FOUND)
      set(_qt_major 6)
      set(_qwt_source "${_qwt_source}: ${_qwt6_library}")
      if(NOT _qwt_source MATCHES "^packaged")
        # A Qwt outside the system's folders (QWT_ROOT, or the one build-qwt-qt6.sh built in the building user's
        # ~/.cache, which no other user can read: issue 36 class 9) is private to Archipelago: copied into the
        # build tree's lib/archipelago (the build tree's programs load it from there, whoever runs them), and
        # installed beside the programs, <prefix>/lib/archipelago (ArchipelagoInstall.cmake).
        _archipelago_private_qwt("${_qwt6_library}")
      endif()
      add_library(Qwt::Qwt UNKNOWN IMPORTED)
      set_target_properties(Qwt::Qwt PROPERTIES IMPORTED_LOCATION "${_qwt6_library}"
        INTERFACE_INCLUDE_DIRECTORIES "${_qwt6_include}")
      set(ARCHIPELAGO_QWT_INCLUDE_DIRS "${_qwt6_include}")
    else()
      message(WARNING "A Qwt for Qt 6 was found (${_qwt6_library}) but Qt 6 was not "
        "(install qt6-base-dev and qt6-svg-dev): using Qt 5")
    endif()
  elseif(_qt_major STREQUAL "6")
    list(JOIN _not_found "\n  " _looked)
    message(FATAL_ERROR "ARCHIPELAGO_QT_MAJOR=6 but no Qwt >= 6.2 built for Qt 6 was found:\n  ${_looked}\n"
      "Run bash scripts/install-deps.sh (it builds one) or pass -DQWT_ROOT=<prefix>.")
  else()
    list(JOIN _not_found "; " _looked)
    message(STATUS "No Qwt for Qt 6 (${_looked}): using Qt 5")
  endif()
endif()

if(NOT _qt_major STREQUAL "6")
  set(_qt_major 5)
  find_package(Qt5 5.15 REQUIRED COMPONENTS Core Gui Widgets Svg PrintSupport Concurrent Test)
  find_path(QWT_QT5_INCLUDE_DIR qwt_global.h PATHS /usr/include/qwt /usr/local/include/qwt)
  find_library(QWT_QT5_LIBRARY NAMES qwt-qt5)
  if(NOT QWT_QT5_INCLUDE_DIR OR NOT QWT_QT5_LIBRARY)
    message(FATAL_ERROR "Qwt for Qt 5 not found: install libqwt-qt5-dev (scripts/install-deps.sh)")
  endif()
  add_library(Qwt::Qwt UNKNOWN IMPORTED)
  set_target_properties(Qwt::Qwt PROPERTIES IMPORTED_LOCATION "${QWT_QT5_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${QWT_QT5_INCLUDE_DIR}")
  set(ARCHIPELAGO_QWT_INCLUDE_DIRS "${QWT_QT5_INCLUDE_DIR}")
  set(_qwt_source "${QWT_QT5_LIBRARY}")
endif()

set(ARCHIPELAGO_QT_MAJOR_USED ${_qt_major})
set(QT_LIB "Qt${_qt_major}")

_archipelago_qwt_header_version("${ARCHIPELAGO_QWT_INCLUDE_DIRS}" _qwt_version)
if(NOT _qwt_version)
  message(FATAL_ERROR "Qwt was found but its qwt_global.h was not (in ${ARCHIPELAGO_QWT_INCLUDE_DIRS})")
endif()
set(_forced "")
if(ARCHIPELAGO_QT_MAJOR)
  set(_forced ", forced by ARCHIPELAGO_QT_MAJOR")
endif()
message(STATUS "Archipelago GUI: Qt ${${QT_LIB}_VERSION}, Qwt ${_qwt_version} (${_qwt_source}${_forced})")
