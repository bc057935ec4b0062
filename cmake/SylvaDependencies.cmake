# Every third-party dependency is a Debian 12 package installed by scripts/setup-debian.sh.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(glm REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(PNG REQUIRED)
find_package(OpenEXR REQUIRED)
find_package(glfw3 REQUIRED)
# SIMD with the best instruction set chosen at run time (Highway): the grass constraint solver's lanes.
find_package(hwy REQUIRED)
include(SylvaThirdParty)
sylva_pkg_config(EPOXY epoxy)
sylva_pkg_config(EGL egl)
if(SYLVA_BUILD_APPS)
  find_package(CLI11 REQUIRED)
  sylva_pkg_config(IMGUI imgui)
endif()
if(SYLVA_BUILD_TESTS)
  find_package(GTest REQUIRED)
  find_program(GLSLANG_VALIDATOR glslangValidator)
endif()
if(SYLVA_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# FFmpeg's libraries (sylva::ffmpeg) and OpenCV (sylva::opencv: the folding editor's motion from video, grass
# capture's contours and distance transforms, texsynth's image reading), made as the installed package makes
# them (cmake/SylvaThirdParty.cmake).
include(SylvaThirdParty)
sylva_ffmpeg_target()
sylva_opencv_target()

