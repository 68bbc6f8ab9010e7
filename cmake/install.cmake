# What `cmake --install build --prefix P` puts where (docs/install.md), and CPack's .deb:
#   bin/terraweave                               the command-line program
#   lib/terraweave/libterraweave_image.so        its OpenImageIO module (loaded on first image)
#   lib/libtw_<module>.a, include/terraweave/    the library (static, one per module) and headers
#   lib/cmake/terraweave/                        find_package(terraweave): terraweave::pipeline ...
#   lib/pkgconfig/terraweave.pc                  pkg-config --cflags --libs terraweave
#   share/terraweave/{kernels,samples,pipelines} OpenCL kernels (found relative to the program),
#                                                the sample data and the pipelines that read it
#   share/terraweave/docs/pipeline.schema.json   the pipelines' JSON Schema (they name it as
#                                                ../docs/pipeline.schema.json, as in the source tree)
#   share/man/man1/terraweave.1, share/bash-completion/completions/terraweave
# Nothing installed names the build or the source tree: the kernels are found relative to the
# program (core/resources.hpp) and three.js is compiled in (src/CMakeLists.txt).
include(CMakePackageConfigHelpers)

set(TW_MODULES core image geo ribbon raster synth terrain ornament sketch network layers pipeline
  commands)
set(TW_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/terraweave)

install(TARGETS terraweave RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# OpenImageIO's side, loaded by the program on its first image (src/cli/image_module_loader.cpp).
install(TARGETS terraweave_image LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/terraweave)
set(tw_libraries tw_warnings)
foreach(m ${TW_MODULES})
  list(APPEND tw_libraries tw_${m})
endforeach()
set_target_properties(tw_warnings PROPERTIES EXPORT_NAME warnings)
install(TARGETS ${tw_libraries} EXPORT terraweaveTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/terraweave)
# Every module's headers, detail/ included (a public header may include its own module's).
foreach(m ${TW_MODULES})
  install(DIRECTORY ${CMAKE_SOURCE_DIR}/src/${m} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/terraweave
    FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(EXPORT terraweaveTargets NAMESPACE terraweave:: DESTINATION ${TW_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/terraweaveConfig.cmake.in
  ${CMAKE_BINARY_DIR}/terraweaveConfig.cmake INSTALL_DESTINATION ${TW_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/terraweaveConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/terraweaveConfig.cmake
  ${CMAKE_BINARY_DIR}/terraweaveConfigVersion.cmake DESTINATION ${TW_CMAKE_DIR})

# pkg-config: the libraries in link order (downstream first), their Debian pkg-config packages.
set(TW_PC_LIBS "")  # CGAL (header-only) needs GMP and MPFR
foreach(m commands pipeline layers network ornament sketch terrain synth raster ribbon geo image core)
  string(APPEND TW_PC_LIBS " -ltw_${m}")
endforeach()
file(RELATIVE_PATH TW_PC_PREFIX "/root/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/root")
configure_file(${CMAKE_SOURCE_DIR}/cmake/terraweave.pc.in ${CMAKE_BINARY_DIR}/terraweave.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/terraweave.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(DIRECTORY ${CMAKE_SOURCE_DIR}/kernels/ DESTINATION ${CMAKE_INSTALL_DATADIR}/terraweave/kernels)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/samples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/terraweave/samples)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/pipelines/
  DESTINATION ${CMAKE_INSTALL_DATADIR}/terraweave/pipelines)
install(FILES ${CMAKE_SOURCE_DIR}/docs/pipeline.schema.json
  DESTINATION ${CMAKE_INSTALL_DATADIR}/terraweave/docs)
install(FILES ${CMAKE_SOURCE_DIR}/docs/man/terraweave.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${CMAKE_SOURCE_DIR}/scripts/completion/terraweave
  DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})

# cpack -G DEB in the build folder: terraweave_<version>_<arch>.deb, installing under /usr, its
# dependencies found by dpkg-shlibdeps from the libraries the program links.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME terraweave)
set(CPACK_PACKAGE_VENDOR terraweave)
set(CPACK_PACKAGE_CONTACT "terraweave maintainers <terraweave@users.noreply.github.com>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "terrain features for procedural worlds from vector maps")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# With TERRAWEAVE_LAZY_GDAL the program names neither libgdal nor cpp-httplib for
# dpkg-shlibdeps to find (it loads them on first use): the packages that hold this build's
# files are named here.
if(TERRAWEAVE_LAZY_GDAL)
  get_target_property(_tw_gdal_file GDAL::GDAL LOCATION)
  set(_tw_lazy_depends)
  foreach(_tw_file IN ITEMS "${_tw_gdal_file}" "${TW_HTTPLIB_FILE}")
    if(NOT _tw_file)
      continue()
    endif()
    file(REAL_PATH "${_tw_file}" _tw_file)
    execute_process(COMMAND dpkg-query -S "${_tw_file}" OUTPUT_VARIABLE _tw_owner
      ERROR_QUIET RESULT_VARIABLE _tw_query)
    if(_tw_query EQUAL 0 AND _tw_owner MATCHES "^([^:, ]+)")
      list(APPEND _tw_lazy_depends "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  list(JOIN _tw_lazy_depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
endif()
# The OpenCL loader (a shlibdeps dependency) finds no device without an ICD; PoCL runs the
# kernels on the CPU. Building against the library needs the -dev packages of its dependencies.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "pocl-opencl-icd | opencl-icd")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
  "libgdal-dev, libgeographiclib-dev, ocl-icd-opencl-dev, opencl-clhpp-headers, libopenimageio-dev, libopenexr-dev, libyaml-cpp-dev, libspdlog-dev, libfmt-dev, libtbb-dev, nlohmann-json3-dev, libeigen3-dev, libboost-dev, libcgal-dev, libxxhash-dev, pkg-config")
include(CPack)
