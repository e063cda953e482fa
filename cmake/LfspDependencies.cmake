# Every third-party dependency is found here, once, so the stage CMakeLists only name targets.
find_package(Threads REQUIRED)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs ximgproc calib3d videoio)  # videoio: MP4 sweeps
find_package(OpenImageIO REQUIRED)
find_package(HDF5 REQUIRED COMPONENTS C CXX)
find_package(ZLIB REQUIRED)  # compresses bundle chunks in parallel (core/src/hdf5_chunks.cc)
find_package(nlohmann_json 3 REQUIRED)
find_package(spdlog REQUIRED)
find_package(CLI11 REQUIRED)
find_package(OpenSSL REQUIRED COMPONENTS Crypto)
find_package(PkgConfig REQUIRED)
pkg_check_modules(MATIO REQUIRED IMPORTED_TARGET matio)  # MATLAB v5 .mat light fields (core/src/mat_light_field.cc)
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)  # `lfsp view`'s local server (apps/view)
find_package(Ceres QUIET)
find_package(GTest)
find_package(benchmark QUIET)

# HDF5's CMake module gives variables, not a target: wrap them once.
if(NOT TARGET lfsp_hdf5)
  add_library(lfsp_hdf5 INTERFACE)
  target_include_directories(lfsp_hdf5 SYSTEM INTERFACE ${HDF5_INCLUDE_DIRS})
  target_link_libraries(lfsp_hdf5 INTERFACE ${HDF5_LIBRARIES} ${HDF5_CXX_LIBRARIES})
  target_compile_definitions(lfsp_hdf5 INTERFACE ${HDF5_DEFINITIONS})
endif()

# OpenCV headers are treated as system headers so our warnings stay about our code.
if(NOT TARGET lfsp_opencv)
  add_library(lfsp_opencv INTERFACE)
  target_include_directories(lfsp_opencv SYSTEM INTERFACE ${OpenCV_INCLUDE_DIRS})
  target_link_libraries(lfsp_opencv INTERFACE ${OpenCV_LIBS})
endif()
