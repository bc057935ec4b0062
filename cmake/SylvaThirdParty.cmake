# Third-party targets that Sylva makes itself, shared by the build (cmake/SylvaDependencies.cmake) and the
# installed package (SylvaConfig.cmake includes this file from lib/cmake/Sylva), so a program linking the
# installed static libraries finds the same libraries the build did.
include_guard(GLOBAL)

# sylva_pkg_config(<NAME> <module>...): PkgConfig::<NAME> from pkg-config modules (REQUIRED); the module list is
# recorded (global property SYLVA_PKG_<NAME>) so the installed package looks up the same ones.
macro(sylva_pkg_config name)
  if(NOT TARGET PkgConfig::${name})
    find_package(PkgConfig REQUIRED)
    pkg_check_modules(${name} REQUIRED IMPORTED_TARGET GLOBAL ${ARGN})
  endif()
  set_property(GLOBAL PROPERTY SYLVA_PKG_${name} ${ARGN})
endmacro()

# sylva::opencv: OpenCV's core, imgproc, video, videoio and imgcodecs, kept out of Sylva's public headers.
# Debian installs OpenCVConfig.cmake only with the libopencv-dev meta package, which pulls every OpenCV module
# (contrib, viz with VTK, Qt); the per-module -dev packages Sylva needs carry the headers and libraries alone,
# so without a config file the same components are found directly.
macro(sylva_opencv_target)
  if(NOT TARGET sylva::opencv)
    add_library(sylva::opencv INTERFACE IMPORTED GLOBAL)
    find_package(OpenCV QUIET COMPONENTS core imgproc video videoio imgcodecs)
    if(OpenCV_FOUND)
      target_include_directories(sylva::opencv SYSTEM INTERFACE ${OpenCV_INCLUDE_DIRS})
      target_link_libraries(sylva::opencv INTERFACE ${OpenCV_LIBS})
    else()
      find_path(SYLVA_OPENCV_INCLUDE_DIR opencv2/video/tracking.hpp PATH_SUFFIXES opencv4 REQUIRED)
      target_include_directories(sylva::opencv SYSTEM INTERFACE ${SYLVA_OPENCV_INCLUDE_DIR})
      foreach(_sylva_cv videoio imgcodecs video imgproc core)
        find_library(SYLVA_OPENCV_${_sylva_cv}_LIBRARY opencv_${_sylva_cv} REQUIRED)
        target_link_libraries(sylva::opencv INTERFACE ${SYLVA_OPENCV_${_sylva_cv}_LIBRARY})
      endforeach()
    endif()
  endif()
endmacro()

# sylva::ffmpeg: FFmpeg's libraries for reference videos in containers (folding: AVI, MP4, WebM, … through
# libavformat, libavcodec and libswscale).
macro(sylva_ffmpeg_target)
  if(NOT TARGET sylva::ffmpeg)
    sylva_pkg_config(LIBAV libavformat libavcodec libswscale libavutil)
    add_library(sylva::ffmpeg INTERFACE IMPORTED GLOBAL)
    target_link_libraries(sylva::ffmpeg INTERFACE PkgConfig::LIBAV)
  endif()
endmacro()
