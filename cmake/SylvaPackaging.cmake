# What the `sylva` program installs beside itself, and the Debian packages (docs/library.md, "The Debian
# packages"): `cpack --config build/release/CPackConfig.cmake` in build/release, or scripts/package.sh, writes
# sylva_<version>_amd64.deb (the program and its data; the shared libraries it uses found by dpkg-shlibdeps)
# and sylva-dev_<version>_amd64.deb (headers, static libraries, the CMake package; it depends on the -dev
# packages of the libraries the static libraries link).
include_guard(GLOBAL)
include(GNUInstallDirs)

# The data the tools need, found through sylva::dataDirectory() as <prefix>/share/sylva/data. The fetched
# third-party samples (data/external) are not the project's to ship, and jacksboro.json needs one of them.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/blades ${PROJECT_SOURCE_DIR}/data/folding
  DESTINATION ${CMAKE_INSTALL_DATADIR}/sylva/data COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/data/scenes/meadow.json
  DESTINATION ${CMAKE_INSTALL_DATADIR}/sylva/data/scenes COMPONENT runtime)

# Debian policy: each package's /usr/share/doc/<package> holds the copyright and a compressed changelog
# (gzip -9n: no name or time stamp, so the package is reproducible).
set(debian_doc ${PROJECT_BINARY_DIR}/package/debian)
file(MAKE_DIRECTORY ${debian_doc})
string(TIMESTAMP changelog_date "%a, %d %b %Y %H:%M:%S +0000" UTC)
file(WRITE ${debian_doc}/changelog
  "sylva (${PROJECT_VERSION}) unstable; urgency=medium\n\n"
  "  * Release ${PROJECT_VERSION}: see /usr/share/doc/sylva/CHANGELOG.md.gz.\n\n"
  " -- Seed ab0b98cc maintainers <maintainers@users.noreply.h-seed-ab0b98cc.example>  ${changelog_date}\n")
find_program(SYLVA_GZIP gzip REQUIRED)
execute_process(COMMAND ${SYLVA_GZIP} -9nf ${debian_doc}/changelog)
execute_process(COMMAND ${SYLVA_GZIP} -9nc ${PROJECT_SOURCE_DIR}/CHANGELOG.md
  OUTPUT_FILE ${debian_doc}/CHANGELOG.md.gz)
foreach(package sylva sylva-dev)
  if(package STREQUAL "sylva")
    set(component runtime)
  else()
    set(component dev)
  endif()
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/install/debian/copyright ${debian_doc}/changelog.gz
    ${debian_doc}/CHANGELOG.md.gz DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${package} COMPONENT ${component})
endforeach()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME sylva)
set(CPACK_PACKAGE_VENDOR "Sylva developers")
set(CPACK_PACKAGE_CONTACT "Seed ab0b98cc maintainers <maintainers@users.noreply.h-seed-ab0b98cc.example>")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
# The prefix the libraries were configured for (the release preset's /usr): sylva::dataDirectory() looks there.
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_PACKAGE_DIRECTORY ${PROJECT_BINARY_DIR}/package)
set(CPACK_STRIP_FILES bin/sylva)
set(CPACK_DEB_COMPONENT_INSTALL ON)
# Each package's synopsis is the first line of its CPACK_DEBIAN_<COMPONENT>_DESCRIPTION, not the project's.
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY IGNORE)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_COMPRESSION_TYPE xz)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME sylva)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
# What dpkg-shlibdeps cannot see: the OpenGL contexts come through glvnd's libEGL (loaded at run time, never
# linked), which needs a vendor driver; Mesa's software rasteriser (llvmpipe, in libgl1-mesa-dri) draws without a
# GPU, a GPU's own EGL driver replaces it. ffmpeg encodes `--mp4`; slurm-client runs `sylva farm`. On a fresh
# Debian 12, `apt install ./sylva_*.deb` without these gave a program that could not render (caught by
# installing the package into a debootstrap root, docs/library.md).
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "libegl1")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "libgl1-mesa-dri")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SUGGESTS "ffmpeg, slurm-client")
# Debian descriptions: a synopsis line, then the long description (CPack indents it).
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION "real-time procedural nature: terrain, grass, trees, folding textures
The sylva program renders scene files of terrain with continuous level of
detail, captured and simulated grass, trees grown from interlocking pieces and
folding textures, headless or in a window, and runs their editors and tools.")
set(CPACK_DEBIAN_DEV_PACKAGE_NAME sylva-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_DESCRIPTION "Sylva engine modules: static libraries, headers and CMake package
The terrain, grass, trees, folding, capture, scene and rendering modules of
Sylva as static libraries with their public headers, for programs that use
find_package(Sylva COMPONENTS ...) and link sylva::<module>.")
# The -dev packages of what the static libraries link (cmake/SylvaDependencies.cmake, scripts/setup-debian.sh).
string(JOIN ", " CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "sylva (= ${PROJECT_VERSION})" cmake pkg-config
  libglm-dev libfmt-dev libspdlog-dev nlohmann-json3-dev libpng-dev libopenexr-dev libglfw3-dev libhwy-dev
  libepoxy-dev libegl-dev libimgui-dev libgdal-dev zlib1g-dev libzip-dev libgif-dev libfreenect-dev
  libbullet-dev libassimp-dev libopencv-core-dev libopencv-imgproc-dev libopencv-video-dev
  libopencv-videoio-dev libavformat-dev libavcodec-dev libswscale-dev libavutil-dev)
include(CPack)
