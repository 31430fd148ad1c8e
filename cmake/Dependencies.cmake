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

# OpenVDB's module lives outside CMake's default search path on Debian, and
# needs Boost iostreams present to configure.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)

if(ROCKBAKE_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(ROCKBAKE_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
