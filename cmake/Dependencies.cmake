# Every third-party library, found the way Debian 12 packages them.
# The quirks each find works around are noted beside it.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(TBB REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(spdlog REQUIRED)
find_package(fmt REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(PNG REQUIRED)
# Libraries (docs/libraries.md): SHA-256 for manifests (OpenSSL's libcrypto); FreeType
# draws the names on contact sheets, in DejaVu Sans (fonts-dejavu-core).
find_package(OpenSSL REQUIRED COMPONENTS Crypto)
find_package(Freetype REQUIRED)

# OpenVDB's find module lives outside CMake's default search path on Debian, in the
# architecture's library folder (lib/x86_64-linux-gnu, lib/aarch64-linux-gnu, …), and
# needs Boost iostreams present to configure.
find_path(OPENVDB_FIND_MODULE_DIR FindOpenVDB.cmake
  PATHS ${CMAKE_PREFIX_PATH} ${CMAKE_SYSTEM_PREFIX_PATH}
  PATH_SUFFIXES lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB lib64/cmake/OpenVDB lib/cmake/OpenVDB
  NO_DEFAULT_PATH)
if(NOT OPENVDB_FIND_MODULE_DIR)
  message(FATAL_ERROR "OpenVDB's FindOpenVDB.cmake was not found under lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB "
                      "of ${CMAKE_SYSTEM_PREFIX_PATH}: install libopenvdb-dev (scripts/setup.sh), or pass "
                      "-DOPENVDB_FIND_MODULE_DIR=<the folder that holds it>")
endif()
list(APPEND CMAKE_MODULE_PATH ${OPENVDB_FIND_MODULE_DIR})
find_package(OpenVDB REQUIRED)

# OpenSubdiv: its CMake package names static libraries Debian does not ship,
# so find the header and the shared CPU library directly.
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/version.h REQUIRED)
find_library(OPENSUBDIV_CPU_LIBRARY osdCPU REQUIRED)
add_library(OpenSubdiv::osdCPU UNKNOWN IMPORTED)
set_target_properties(OpenSubdiv::osdCPU PROPERTIES
  IMPORTED_LOCATION ${OPENSUBDIV_CPU_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES ${OPENSUBDIV_INCLUDE_DIR})

# tinygltf: Debian ships the implementation as a shared library with a CMake
# config (TinyGLTF::TinyGLTF); meshoptimizer has its own config.
find_package(TinyGLTF REQUIRED)
find_package(meshoptimizer REQUIRED)

# Qhull (docs/collision.md): the C++ interface, Qhull::qhullcpp, sits on the
# reentrant C library, Qhull::qhull_r, which has to be linked as well.
find_package(Qhull REQUIRED)

# The texture stage (docs/textures.md): Embree 3 casts the bake's rays, Eigen's sparse
# Cholesky solves each chart's LSCM system, zlib compresses the maps' PNGs in parallel
# bands (texture/png_encoder.h).
find_package(embree 3 REQUIRED)
find_package(Eigen3 REQUIRED NO_MODULE)
find_package(ZLIB REQUIRED)

if(ROCKBAKE_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(ROCKBAKE_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# Rendering (docs/rendering.md): OpenEXR's own CMake config; OpenColorIO through
# pkg-config, because its CMake package computes a wrong prefix on Debian.
find_package(OpenEXR CONFIG REQUIRED)
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO)
