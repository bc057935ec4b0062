include_guard(GLOBAL)
include(GNUInstallDirs)
include(SylvaInstall)

# Warnings for our own code only; third-party headers are included as SYSTEM.
set(SYLVA_WARNINGS -Wall -Wextra -Wpedantic -Werror -Wno-missing-field-initializers)

# sylva_add_module(<name> DEPS <targets...> [PRIVATE_DEPS <targets...>])
# Creates target sylva_<name> with alias sylva::<name> from engine/<name>/src/*.cpp, public headers under
# engine/<name>/include (included as <sylva/<name>/X.hpp>), private headers under src/internal.
function(sylva_add_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  if(NOT sources)
    message(STATUS "Sylva module '${name}' has no sources yet; skipped")
    return()
  endif()
  add_library(sylva_${name} STATIC ${sources})
  add_library(sylva::${name} ALIAS sylva_${name})
  target_include_directories(sylva_${name}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(sylva_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_options(sylva_${name} PRIVATE ${SYLVA_WARNINGS})
  # Unity batches: each file parses the same heavy headers (OpenCV, Bullet, glm, fmt, spdlog, nlohmann) again;
  # a batch parses them once (docs/testing.md, "Where the time goes").
  set_target_properties(sylva_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON
    UNITY_BUILD ${SYLVA_UNITY_BUILD} UNITY_BUILD_BATCH_SIZE 6)
  sylva_install_module(sylva_${name} ${name} ${CMAKE_CURRENT_SOURCE_DIR}/include)
endfunction()

# sylva_add_gpu_module(<name> DEPS <targets...>)
# The GL side of module <name> (sources in gpu/*.cpp) as sylva::<name>_gpu, linked to sylva::<name>, to the
# GL side of render (sylva::render_gpu: targets, timers, frame uniforms) and DEPS: decide on the CPU
# (sylva::<name>, unit-tested without GL), draw on the GPU. Skipped without sylva::render_gpu (except for
# render's own) or without sources.
function(sylva_add_gpu_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB gpu_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/gpu/*.cpp)
  set(render_gpu sylva::render_gpu)
  if(name STREQUAL "render")
    set(render_gpu)
  elseif(NOT TARGET sylva::render_gpu)
    return()
  endif()
  if(NOT TARGET sylva_${name} OR NOT gpu_sources)
    return()
  endif()
  add_library(sylva_${name}_gpu STATIC ${gpu_sources})
  add_library(sylva::${name}_gpu ALIAS sylva_${name}_gpu)
  target_include_directories(sylva_${name}_gpu
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(sylva_${name}_gpu PUBLIC sylva::${name} ${render_gpu} ${ARG_DEPS})
  target_compile_options(sylva_${name}_gpu PRIVATE ${SYLVA_WARNINGS})
  set_target_properties(sylva_${name}_gpu PROPERTIES UNITY_BUILD ${SYLVA_UNITY_BUILD} UNITY_BUILD_BATCH_SIZE 6)
  sylva_install_module(sylva_${name}_gpu ${name}_gpu "")
endfunction()

# sylva_use_shared_layouts(<target>): <target> includes the GPU layouts as <shared/X.h> (shaders/shared), from
# the source tree when built here and from include/sylva/shaders once installed.
function(sylva_use_shared_layouts target)
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${SYLVA_SHADER_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/sylva/shaders>)
endfunction()

# sylva_add_test(<name> LABEL unit|gl|golden SOURCES <files...> DEPS <targets...> [LOCK <resource>]
#                [FILTER <gtest filter>])
# One GoogleTest executable per (module, tier); every test case becomes a CTest test carrying the label.
# LOCK: a CTest RESOURCE_LOCK shared by executables whose tests must not run at the same time.
# FILTER: only the test cases the filter selects become CTest tests (one source split over two tiers).
function(sylva_add_test name)
  cmake_parse_arguments(ARG "" "LABEL;LOCK;FILTER" "SOURCES;DEPS" ${ARGN})
  if(NOT ARG_SOURCES)
    message(STATUS "Test ${name} has no sources yet; skipped")
    return()
  endif()
  add_executable(${name} ${ARG_SOURCES})
  # Unity batches: GoogleTest's headers cost more than most test files (docs/testing.md, "Where the time goes").
  set_target_properties(${name} PROPERTIES UNITY_BUILD ${SYLVA_UNITY_BUILD} UNITY_BUILD_BATCH_SIZE 8)
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock)
  # The code under test is the libraries', built as shipped; the test code itself compiles at -O1 in Release
  # builds, 38 % faster than at -O3 (docs/testing.md, "Where the time goes").
  target_compile_options(${name} PRIVATE ${SYLVA_WARNINGS} $<$<CONFIG:Release>:-O1>)
  target_compile_definitions(${name} PRIVATE
    SYLVA_SOURCE_DIR="${PROJECT_SOURCE_DIR}" SYLVA_BINARY_DIR="${PROJECT_BINARY_DIR}")
  set(lock)
  if(ARG_LOCK)
    set(lock RESOURCE_LOCK ${ARG_LOCK})
  endif()
  set(filter)
  if(ARG_FILTER)
    set(filter TEST_FILTER ${ARG_FILTER})
  endif()
  string(REGEX REPLACE "^sylva_(unit|gl|golden)_" "" module ${name})
  if(module MATCHES "^sylva_cli")
    set(module cli)
  endif()
  if(SYLVA_BATCH_UNIT_TESTS AND ARG_LABEL STREQUAL "unit")
    # One CTest test per suite (cmake/GTestSuites.cmake): the sanitizer builds, where starting a process costs
    # more than most unit tests.
    set(suites_file ${CMAKE_CURRENT_BINARY_DIR}/${name}_suites.cmake)
    string(CONCAT content
      "set(SYLVA_SUITES_EXE [==[$<TARGET_FILE:${name}>]==])\n"
      "set(SYLVA_SUITES_FILTER [==[${ARG_FILTER}]==])\n"
      "set(SYLVA_SUITES_LABELS [==[${ARG_LABEL};module:${module}]==])\n"
      "set(SYLVA_SUITES_LOCK [==[${ARG_LOCK}]==])\n"
      "include([==[${PROJECT_SOURCE_DIR}/cmake/GTestSuites.cmake]==])\n")
    file(GENERATE OUTPUT ${suites_file} CONTENT "${content}")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${suites_file})
    add_dependencies(sylva_tests_${ARG_LABEL} ${name})
    return()
  endif()
  gtest_discover_tests(${name} ${filter}
    DISCOVERY_MODE PRE_TEST
    PROPERTIES LABELS ${ARG_LABEL} ENVIRONMENT "SYLVA_TEST_LABEL=${ARG_LABEL}" ${lock}
    DISCOVERY_TIMEOUT 60)
  # A second label names the module (sylva_<tier>_<module>; module:cli for tests of the sylva program), so
  # scripts/quick-test.sh can run the gl tests of the modules a change touches. gtest_discover_tests passes its
  # PROPERTIES on as one flat list (a list value would split into property names), so the labels are set by a
  # script CTest includes after the discovered tests, over the list discovery leaves in ${name}_TESTS.
  set(labels_file ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
  file(WRITE ${labels_file}
    "foreach(test IN LISTS ${name}_TESTS)\n"
    "  set_tests_properties(\"\${test}\" PROPERTIES LABELS \"${ARG_LABEL};module:${module}\")\n"
    "endforeach()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${labels_file})
  add_dependencies(sylva_tests_${ARG_LABEL} ${name})
endfunction()

# sylva_embed_directory(<target> <dir> <namespace-function>)
# Generates a C++ source that holds every file under <dir> (shaders) as a byte array, keyed by its path relative
# to <dir>, so the binary never depends on the working directory.
function(sylva_embed_directory target dir)
  file(GLOB_RECURSE files CONFIGURE_DEPENDS RELATIVE ${dir}
    ${dir}/*.glsl ${dir}/*.h ${dir}/*.vert ${dir}/*.frag ${dir}/*.tesc ${dir}/*.tese ${dir}/*.geom ${dir}/*.comp)
  list(SORT files)
  set(abs_files)
  foreach(f ${files})
    list(APPEND abs_files ${dir}/${f})
  endforeach()
  set(out ${CMAKE_CURRENT_BINARY_DIR}/EmbeddedShaders.cpp)
  string(REPLACE ";" "|" files_arg "${files}")
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DDIR=${dir} -DOUT=${out} "-DFILES=${files_arg}"
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    DEPENDS ${abs_files} ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    COMMENT "Embedding shaders from ${dir}" VERBATIM)
  target_sources(${target} PRIVATE ${out})
endfunction()

# sylva_module_enabled(<module> <out-var>): TRUE unless SYLVA_MODULES restricts the build to other modules.
function(sylva_module_enabled module out)
  if(NOT SYLVA_MODULES OR module IN_LIST SYLVA_MODULES OR module STREQUAL "support")
    set(${out} TRUE PARENT_SCOPE)
  else()
    set(${out} FALSE PARENT_SCOPE)
  endif()
endfunction()
