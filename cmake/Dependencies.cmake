# Every third-party library, found the way Debian 12 packages them.
# See docs/dependencies.md for the quirks this file works around.
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

# OpenVDB's module lives outside CMake's default search path on Debian, and
# needs Boost iostreams present to configure.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
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
