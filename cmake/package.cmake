# Installation layout and the Debian package (scripts/package.sh runs `cpack -G DEB` in the build
# folder): aggpack, aggpack-gui with its desktop entry and icon, the Python module in Debian's
# dist-packages, man pages made by help2man from the CLI's own help, docs and examples under
# share/doc/aggpack. Depends come from the libraries the programs actually link (dpkg-shlibdeps)
# plus the interpreter and numpy the module imports.
include(GNUInstallDirs)

install(TARGETS aggpack RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET aggpack-gui)
  install(TARGETS aggpack-gui RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(FILES packaging/aggpack-gui.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
  install(FILES packaging/aggpack.svg DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps)
endif()
set(AGGPACK_DOC_DIR ${CMAKE_INSTALL_DATADIR}/doc/aggpack)
install(FILES README.md CHANGELOG.md packaging/copyright DESTINATION ${AGGPACK_DOC_DIR})
install(DIRECTORY docs/ DESTINATION ${AGGPACK_DOC_DIR}/docs)
install(DIRECTORY examples/ DESTINATION ${AGGPACK_DOC_DIR}/examples)

# Man pages: aggpack(1) and aggpack-SUB(1) for every subcommand, when help2man is installed.
find_program(AGGPACK_HELP2MAN help2man)
if(AGGPACK_HELP2MAN AND NOT CMAKE_CROSSCOMPILING)
  set(man_dir ${PROJECT_BINARY_DIR}/man)
  add_custom_command(
    OUTPUT ${man_dir}/pages.txt
    COMMAND ${CMAKE_COMMAND} -DAGGPACK=$<TARGET_FILE:aggpack> -DVERSION=${PROJECT_VERSION}
            -DOUT=${man_dir} -P ${PROJECT_SOURCE_DIR}/cmake/man_pages.cmake
    DEPENDS aggpack ${PROJECT_SOURCE_DIR}/cmake/man_pages.cmake
    COMMENT "Man pages (help2man)")
  add_custom_target(aggpack_man_pages ALL DEPENDS ${man_dir}/pages.txt)
  install(DIRECTORY ${man_dir}/ DESTINATION ${CMAKE_INSTALL_MANDIR}/man1
          FILES_MATCHING PATTERN "*.1.gz")
else()
  message(STATUS "aggpack: no man pages (apt-get install help2man)")
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME aggpack)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "aggpack developers")
set(CPACK_PACKAGE_CONTACT "aggpack developers <aggpack@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # aggpack_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "random aggregate particles: generation, packing, models")
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "random aggregate particles: generation, packing, models
 aggpack grows irregular convex particles (rock, ballast, concrete aggregate),
 packs them into a container without overlap and turns the packing into files
 for 3D printing, finite-element and DEM models (CalculiX/Abaqus, Gmsh,
 LS-DYNA, ANSYS, YADE), concrete mesomodels, pictures and an angle-of-repose
 test. Command line (aggpack), graphical program (aggpack-gui) and a Python
 module (import aggpack).")
if(TARGET aggpack_python)
  # The module is built for one interpreter version (e.g. 3.11): python3 (>= 3.11~, << 3.12).
  string(REPLACE "." ";" python_version "${AGGPACK_PYTHON_VERSION}")
  list(GET python_version 0 python_major)
  list(GET python_version 1 python_minor)
  math(EXPR python_next "${python_minor} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= ${python_major}.${python_minor}~), \
python3 (<< ${python_major}.${python_next}), python3-numpy")
endif()
# Readers and solvers the exports and commands can hand their files to.
# aggpack-gui shows Chinese (zh_* locales, View > Language) with a CJK font, else English.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "fonts-noto-cjk | fonts-wqy-microhei")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "calculix-ccx, gmsh, yade, paraview, gnuplot-nox")
include(CPack)
