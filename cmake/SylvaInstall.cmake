# Install rules and the exported CMake package (docs/library.md): every engine module is a component of
# find_package(Sylva COMPONENTS …), its static library under lib/, its headers under include/sylva/<module>/,
# its imported target sylva::<module> in lib/cmake/Sylva/Sylva_<module>.cmake. SylvaConfig.cmake loads the
# components asked for, the Sylva components they link and the third-party packages those need
# (SylvaComponents.cmake, written here from the targets' own link libraries, so it cannot fall out of date).
include_guard(GLOBAL)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(SYLVA_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Sylva)

# sylva_install_module(<target> <component> <include dir or "">): installs <target> as sylva::<component>.
function(sylva_install_module target component include_dir)
  sylva_install_extra(${target} ${component} ${component})
  set_property(GLOBAL APPEND PROPERTY SYLVA_COMPONENTS ${component})
  if(include_dir)
    install(DIRECTORY ${include_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)
  endif()
endfunction()

# sylva_install_extra(<target> <component> <export name>): installs <target> as sylva::<export name> in the
# export set of <component> (a library a module links that is built here, e.g. the ImGui backends).
function(sylva_install_extra target component export_name)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
  install(TARGETS ${target} EXPORT Sylva_${component}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
  set_property(GLOBAL APPEND PROPERTY SYLVA_COMPONENT_TARGETS_${component} ${target})
  set_property(GLOBAL PROPERTY SYLVA_TARGET_COMPONENT_${target} ${component})
endfunction()

# The package a third-party link library comes from, as SylvaConfig.cmake finds it: a find_package name,
# pkg:<NAME> (PkgConfig::<NAME>, sylva_pkg_config), or opencv/ffmpeg (cmake/SylvaThirdParty.cmake).
function(_sylva_package_of lib out)
  set(known glm::glm=glm fmt::fmt=fmt spdlog::spdlog=spdlog nlohmann_json::nlohmann_json=nlohmann_json
    Threads::Threads=Threads PNG::PNG=PNG OpenEXR::OpenEXR=OpenEXR GDAL::GDAL=GDAL ZLIB::ZLIB=ZLIB GIF::GIF=GIF
    glfw=glfw3 hwy::hwy=hwy sylva::opencv=opencv sylva::ffmpeg=ffmpeg)
  foreach(pair ${known})
    string(REPLACE "=" ";" pair ${pair})
    list(GET pair 0 name)
    if(lib STREQUAL name)
      list(GET pair 1 package)
      set(${out} ${package} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  if(lib MATCHES "^PkgConfig::(.+)$")
    set(${out} pkg:${CMAKE_MATCH_1} PARENT_SCOPE)
    return()
  endif()
  message(FATAL_ERROR "cmake/SylvaInstall.cmake: the installed package cannot find '${lib}' for its users; "
    "add it to _sylva_package_of")
endfunction()

# sylva_install_package(): the export files, SylvaComponents.cmake, the config and version files. Called once,
# after every module is defined.
function(sylva_install_package)
  get_property(components GLOBAL PROPERTY SYLVA_COMPONENTS)
  set(table "# Written by cmake/SylvaInstall.cmake: each component, the Sylva components it links (static\n")
  string(APPEND table "# libraries need their private ones too) and the third-party packages it needs.\n")
  set(pkg_names)
  foreach(component ${components})
    get_property(targets GLOBAL PROPERTY SYLVA_COMPONENT_TARGETS_${component})
    set(requires)
    set(packages)
    foreach(target ${targets})
      get_target_property(libs ${target} LINK_LIBRARIES)
      if(NOT libs)
        continue()
      endif()
      foreach(lib ${libs})
        set(real ${lib})
        if(TARGET ${lib})
          get_target_property(aliased ${lib} ALIASED_TARGET)
          if(aliased)
            set(real ${aliased})
          endif()
        endif()
        get_property(dep GLOBAL PROPERTY SYLVA_TARGET_COMPONENT_${real})
        if(dep)
          if(NOT dep STREQUAL component)
            list(APPEND requires ${dep})
          endif()
        else()
          _sylva_package_of(${lib} package)
          list(APPEND packages ${package})
          if(package MATCHES "^pkg:(.+)$")
            list(APPEND pkg_names ${CMAKE_MATCH_1})
          endif()
        endif()
      endforeach()
    endforeach()
    list(REMOVE_DUPLICATES requires)
    list(REMOVE_DUPLICATES packages)
    set(requires_${component} ${requires})
    string(APPEND table "set(_sylva_requires_${component} ${requires})\n")
    string(APPEND table "set(_sylva_packages_${component} ${packages})\n")
    install(EXPORT Sylva_${component} NAMESPACE sylva:: DESTINATION ${SYLVA_INSTALL_CMAKEDIR}
      FILE Sylva_${component}.cmake COMPONENT dev)
  endforeach()
  # Dependencies first (a module may link one defined after it, as trees links texsynth), so SylvaConfig.cmake
  # loads each component's export file after those it refers to.
  set(ordered)
  set(left ${components})
  while(left)
    set(progress FALSE)
    foreach(component ${left})
      set(ready TRUE)
      foreach(dep ${requires_${component}})
        if(NOT dep IN_LIST ordered)
          set(ready FALSE)
        endif()
      endforeach()
      if(ready)
        list(APPEND ordered ${component})
        list(REMOVE_ITEM left ${component})
        set(progress TRUE)
      endif()
    endforeach()
    if(NOT progress)
      message(FATAL_ERROR "cmake/SylvaInstall.cmake: the modules ${left} depend on each other in a cycle")
    endif()
  endwhile()
  string(APPEND table "set(_sylva_components ${ordered})\n")
  list(APPEND pkg_names LIBAV)
  list(REMOVE_DUPLICATES pkg_names)
  foreach(name ${pkg_names})
    get_property(modules GLOBAL PROPERTY SYLVA_PKG_${name})
    string(APPEND table "set(_sylva_pkg_${name} ${modules})\n")
  endforeach()
  file(WRITE ${PROJECT_BINARY_DIR}/package/SylvaComponents.cmake "${table}")
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/install/SylvaConfig.cmake.in
    ${PROJECT_BINARY_DIR}/package/SylvaConfig.cmake INSTALL_DESTINATION ${SYLVA_INSTALL_CMAKEDIR})
  # Semantic versioning (CHANGELOG.md): while the major version is 0 a minor release may change the API, so a
  # request for 0.2 takes any 0.2.x and no other; from 1.0 on, any later release of the same major version.
  if(PROJECT_VERSION_MAJOR EQUAL 0)
    set(compatibility SameMinorVersion)
  else()
    set(compatibility SameMajorVersion)
  endif()
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/SylvaConfigVersion.cmake
    COMPATIBILITY ${compatibility})
  install(FILES ${PROJECT_BINARY_DIR}/package/SylvaConfig.cmake ${PROJECT_BINARY_DIR}/package/SylvaConfigVersion.cmake
    ${PROJECT_BINARY_DIR}/package/SylvaComponents.cmake ${PROJECT_SOURCE_DIR}/cmake/SylvaThirdParty.cmake
    DESTINATION ${SYLVA_INSTALL_CMAKEDIR} COMPONENT dev)
  # The GPU layouts the public headers include as <shared/X.h> (sylva_use_shared_layouts).
  install(DIRECTORY ${SYLVA_SHADER_DIR}/shared DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sylva/shaders
    COMPONENT dev)
endfunction()
