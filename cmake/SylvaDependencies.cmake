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
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
if(SYLVA_BUILD_APPS)
  find_package(CLI11 REQUIRED)
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
endif()
if(SYLVA_BUILD_TESTS)
  find_package(GTest REQUIRED)
  find_program(GLSLANG_VALIDATOR glslangValidator)
endif()
if(SYLVA_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# FFmpeg's libraries for reference videos in containers (folding: AVI, MP4, WebM, … through libavformat,
# libavcodec and libswscale; engine/folding/src/internal/VideoFile.hpp), found through their pkg-config files.
pkg_check_modules(LIBAV REQUIRED IMPORTED_TARGET libavformat libavcodec libswscale libavutil)
add_library(sylva_ffmpeg INTERFACE)
target_link_libraries(sylva_ffmpeg INTERFACE PkgConfig::LIBAV)

# OpenCV for the folding editor's motion from video (video: DIS and Farneback optical flow; videoio: image
# sequences and the MJPEG writer) and for grass capture (imgproc: contours, Canny, morphology,
# distance transform). Used as the interface target sylva_opencv, kept out of public headers.
# Debian installs OpenCVConfig.cmake only with the libopencv-dev meta package, which pulls every OpenCV module
# (contrib, viz with VTK, Qt); the four per-module -dev packages we install carry the headers and libraries
# alone, so without a config file the same components are found directly.
find_package(OpenCV QUIET COMPONENTS core imgproc video videoio)
add_library(sylva_opencv INTERFACE)
if(OpenCV_FOUND)
  target_include_directories(sylva_opencv SYSTEM INTERFACE ${OpenCV_INCLUDE_DIRS})
  target_link_libraries(sylva_opencv INTERFACE ${OpenCV_LIBS})
else()
  find_path(SYLVA_OPENCV_INCLUDE_DIR opencv2/video/tracking.hpp PATH_SUFFIXES opencv4 REQUIRED)
  target_include_directories(sylva_opencv SYSTEM INTERFACE ${SYLVA_OPENCV_INCLUDE_DIR})
  foreach(component videoio video imgproc core)
    find_library(SYLVA_OPENCV_${component}_LIBRARY opencv_${component} REQUIRED)
    target_link_libraries(sylva_opencv INTERFACE ${SYLVA_OPENCV_${component}_LIBRARY})
  endforeach()
endif()

