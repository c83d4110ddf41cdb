# Chooses the Qt major version from the Qwt that is available, and defines Qwt::Qwt.
#
#  * Qt 6 when a Qwt built for Qt 6 is found: a `Qt6Qwt6` CMake package (Qwt >= 6.2 built with CMake),
#    or an install tree given by -DQWT_ROOT=<prefix> holding include/qwt*.h and lib/libqwt*.
#  * Otherwise Qt 5.15 with Debian's libqwt-qt5-dev (headers in /usr/include/qwt, library libqwt-qt5),
#    which ships no CMake config.
# -DARCHIPELAGO_QT_MAJOR=5|6 forces a choice.

set(ARCHIPELAGO_QT_MAJOR "" CACHE STRING "Force the Qt major version (5 or 6); empty = choose from the Qwt found")
set(QWT_ROOT "" CACHE PATH "Prefix of a Qwt built for Qt 6 (optional)")

set(_qt_major "${ARCHIPELAGO_QT_MAJOR}")

if(NOT _qt_major OR _qt_major STREQUAL "6")
  find_package(Qt6Qwt6 QUIET CONFIG)
  if(Qt6Qwt6_FOUND)
    set(_qt_major 6)
    if(TARGET Qt6Qwt6::qwt AND NOT TARGET Qwt::Qwt)
      add_library(Qwt::Qwt ALIAS Qt6Qwt6::qwt)
    endif()
    set(ARCHIPELAGO_QWT_INCLUDE_DIRS ${QWT_INCLUDE_DIRS})
  elseif(QWT_ROOT)
    find_path(_qwt6_include qwt_global.h PATHS "${QWT_ROOT}/include" "${QWT_ROOT}/include/qwt"
      "${QWT_ROOT}/include/qt6/qwt" NO_DEFAULT_PATH)
    find_library(_qwt6_library NAMES qwt qwt-qt6 PATHS "${QWT_ROOT}/lib" "${QWT_ROOT}/lib64" NO_DEFAULT_PATH)
    if(_qwt6_include AND _qwt6_library)
      set(_qt_major 6)
      add_library(Qwt::Qwt UNKNOWN IMPORTED)
      set_target_properties(Qwt::Qwt PROPERTIES IMPORTED_LOCATION "${_qwt6_library}"
        INTERFACE_INCLUDE_DIRECTORIES "${_qwt6_include}")
      set(ARCHIPELAGO_QWT_INCLUDE_DIRS ${_qwt6_include})
    elseif(_qt_major STREQUAL "6")
      message(FATAL_ERROR "Qt 6 was requested but no Qwt for Qt 6 was found under QWT_ROOT=${QWT_ROOT}")
    endif()
  elseif(_qt_major STREQUAL "6")
    message(FATAL_ERROR "Qt 6 was requested but no Qwt built for Qt 6 was found (Qt6Qwt6 package or -DQWT_ROOT)")
  endif()
endif()

if(NOT _qt_major)
  set(_qt_major 5)
endif()

set(_qt_components Core Gui Widgets Svg PrintSupport Concurrent Test)
if(_qt_major STREQUAL "6")
  find_package(Qt6 6.2 REQUIRED COMPONENTS ${_qt_components} SvgWidgets)
else()
  find_package(Qt5 5.15 REQUIRED COMPONENTS ${_qt_components})
  if(NOT TARGET Qwt::Qwt)
    find_path(QWT_QT5_INCLUDE_DIR qwt_global.h PATHS /usr/include/qwt /usr/local/include/qwt)
    find_library(QWT_QT5_LIBRARY NAMES qwt-qt5 qwt)
    if(NOT QWT_QT5_INCLUDE_DIR OR NOT QWT_QT5_LIBRARY)
      message(FATAL_ERROR "Qwt for Qt 5 not found: install libqwt-qt5-dev (scripts/install-deps.sh)")
    endif()
    add_library(Qwt::Qwt UNKNOWN IMPORTED)
    set_target_properties(Qwt::Qwt PROPERTIES IMPORTED_LOCATION "${QWT_QT5_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${QWT_QT5_INCLUDE_DIR}")
    set(ARCHIPELAGO_QWT_INCLUDE_DIRS ${QWT_QT5_INCLUDE_DIR})
  endif()
endif()

set(ARCHIPELAGO_QT_MAJOR_USED ${_qt_major})
set(QT_LIB "Qt${_qt_major}")

# Qwt's headers (ARCHIPELAGO_QWT_INCLUDE_DIRS, set above for each way of finding Qwt) and its version, read
# from its header so that the configure log can print it.
if(NOT ARCHIPELAGO_QWT_INCLUDE_DIRS)
  message(FATAL_ERROR "Qwt was found but its include directory was not")
endif()
set(_qwt_version "unknown")
foreach(_dir IN LISTS ARCHIPELAGO_QWT_INCLUDE_DIRS)
  if(EXISTS "${_dir}/qwt_global.h")
    file(STRINGS "${_dir}/qwt_global.h" _qwt_line REGEX "define[ \t]+QWT_VERSION_STR")
    string(REGEX MATCH "\"[0-9.]+\"" _qwt_version "${_qwt_line}")
    string(REPLACE "\"" "" _qwt_version "${_qwt_version}")
  endif()
endforeach()
message(STATUS "Archipelago GUI: Qt ${${QT_LIB}_VERSION}, Qwt ${_qwt_version}")

