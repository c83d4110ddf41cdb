# The Debian package (issue 42): CPack's DEB generator packs what `cmake --install` installs (the programs, their
# manual pages, the desktop entry, icon and metainfo, the Python module, the private Qwt), under /usr:
#
#   cpack --config build/default/CPackConfig.cmake -B <folder>     # <folder>/archipelago_<version>_<arch>.deb
#
# CPack rather than debian/ + dpkg-buildpackage: it packs the build tree that was built and tested, with the one
# set of install rules (no second description of what goes where, no second build of ~15 minutes), and takes
# seconds; dpkg-shlibdeps still declares the dependencies from the libraries actually linked.  What Debian's
# policy adds to `cmake --install` (the Python module in /usr/lib/python3/dist-packages, compressed manual pages,
# /usr/share/doc/archipelago/{copyright,changelog.gz}) is done by cmake/DebianLayout.cmake on CPack's staging tree.
# The test package.deb (tests/package, label package, not in the default test run) builds and installs it.

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME archipelago)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})  # the one place: project() in CMakeLists.txt
set(CPACK_PACKAGE_VENDOR "the Archipelago authors")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "stickiness of islands around islands in area-preserving maps")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # archipelago_<version>_<arch>.deb
set(ARCHIPELAGO_PACKAGE_MAINTAINER "Archipelago authors <archipelago@users.noreply.github.com>" CACHE STRING
  "The Maintainer field of the Debian package (Name <address>)")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${ARCHIPELAGO_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# The synopsis is CPACK_PACKAGE_DESCRIPTION_SUMMARY; this is the extended description under it.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "Archipelago explores how the islands around islands in the chaotic sea of an
area-preserving map trap orbits for very long times, and what that does to
correlations and diffusion. It reproduces and extends C. F. F. Karney,
Long-time correlations in the stochastic regime, Physica D 8 (1983) 360-380,
iterating the paper's quadratic map exactly, in 52-bit fixed point, so that
every result is reproducible bit for bit on any machine, thread count or
instruction set.
.
The package holds the desktop application (archipelago), the headless tool
(archipelago-cli), the MPI launcher (archipelago-mpi, when built with MPI), the
paper's report (archipelago-reproduce) and the Python module (import
archipelago).")
# Depends from the libraries the programs link (dpkg-shlibdeps; the private Qwt is found through the programs'
# run path, $ORIGIN/../lib/archipelago).  The Python module needs python3 (its ABI) and returns NumPy arrays.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
if(ARCHIPELAGO_PRIVATE_QWT_FILES)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS "${CMAKE_BINARY_DIR}/${ARCHIPELAGO_PRIVATE_LIBDIR}")
endif()
if(TARGET archipelago_python)
  get_property(python_version GLOBAL PROPERTY ARCHIPELAGO_MODULE_PYTHON_VERSION)
  string(REGEX REPLACE "^([0-9]+)\\.([0-9]+)$" "\\1.\\2" python_version "${python_version}")
  math(EXPR next_minor "${CMAKE_MATCH_2} + 1")
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "python3 (>= ${python_version}), python3 (<< ${CMAKE_MATCH_1}.${next_minor}), python3-numpy")
  get_property(CPACK_ARCHIPELAGO_PYTHON_DIR GLOBAL PROPERTY ARCHIPELAGO_PYTHON_INSTALL_DIR)
endif()
# Maintainer scripts: the module byte-compiled (postinst) and its bytecode removed (prerm, postrm on purge).
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${PROJECT_SOURCE_DIR}/resources/debian/postinst"
  "${PROJECT_SOURCE_DIR}/resources/debian/prerm" "${PROJECT_SOURCE_DIR}/resources/debian/postrm")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# For cmake/DebianLayout.cmake, run by cpack on the staging tree before it packs.
set(CPACK_ARCHIPELAGO_SOURCE_DIR "${PROJECT_SOURCE_DIR}")
set(CPACK_PRE_BUILD_SCRIPTS "${PROJECT_SOURCE_DIR}/cmake/DebianLayout.cmake")
include(CPack)

# package.deb: the package built, installed with apt-get, used from PATH, checked by lintian and purged (issue 42).
# It installs into the system (root only), so it has the label `package`, which the test presets leave out:
#   ctest --test-dir build/default -L package --output-on-failure        (.ci/run does, after the Qt 6 suite)
if(ARCHIPELAGO_BUILD_TESTS AND NOT CMAKE_CXX_FLAGS MATCHES "-fsanitize")
  add_test(NAME package.deb COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/package/test_package.py
    ${CMAKE_CPACK_COMMAND} ${CMAKE_BINARY_DIR} "${installed_programs}" "${ARCHIPELAGO_MAN_PAGES}")
  set_tests_properties(package.deb PROPERTIES LABELS package TIMEOUT 1800 RUN_SERIAL ON)
endif()
