# The Debian package (`make package`, or `cpack -G DEB` in the build folder): the lfsp command, its man pages, the
# Python module (in the interpreter's site-packages: /usr/lib/python3/dist-packages for Debian's python3), the workflow and the samples under
# /usr/share/lfsp, the README, changelog and citation under /usr/share/doc/lfsp. The version is lfsp's own
# (cmake/LfspVersion.cmake); dpkg-shlibdeps works out the shared libraries it depends on.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME lfsp)
set(CPACK_PACKAGE_VERSION "${LFSP_VERSION}")
set(CPACK_PACKAGE_VENDOR "lfsp developers")
set(CPACK_PACKAGE_CONTACT "lfsp developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "light-field superpixels for lenslet (Lytro) cameras")
set(CPACK_PACKAGE_DESCRIPTION
    "Decodes Lytro F01 and Illum captures into 4D light fields, estimates depth, segments them into light-field "
    "superpixels (LFSP), edits, refocuses and scores them; a command line (lfsp), a Python module (import lfsp) and "
    "a Snakemake workflow.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_INSTALL_PREFIX /usr)  # the prefix CPack installs with when staging through DESTDIR (below)
set(CPACK_STRIP_FILES ON)
# Staged through DESTDIR, so an absolute destination (the Python module's site-packages) lands at that path inside
# the package rather than on this machine.
set(CPACK_SET_DESTDIR ON)
set(CPACK_OUTPUT_FILE_PREFIX packages)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
if(LFSP_BUILD_PYTHON)
  # The extension module is built for this interpreter's minor version.
  math(EXPR _lfsp_next_minor "${Python_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}), \
python3 (<< ${Python_VERSION_MAJOR}.${_lfsp_next_minor}), python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "snakemake")
# Only what users run: not the test or benchmark tools a dependency may install.
set(CPACK_COMPONENTS_ALL cli python workflow samples)
set(CPACK_DEB_COMPONENT_INSTALL OFF)
include(CPack)
