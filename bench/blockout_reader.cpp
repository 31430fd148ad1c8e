// The blockout reader alone (inputs/mesh_reader.h): reads one file and prints
// its mesh's size and the process's peak resident memory, before and after
// (bench/blockout_memory.sh runs it).
#include <sys/resource.h>

#include <cstdio>
#include <exception>

#include "inputs/mesh_reader.h"

namespace {

double peakMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: rockbake_blockout_reader FILE.obj|.ply|.stl\n");
    return 2;
  }
  const double before = peakMiB();
  try {
    const rockbake::TriangleMesh mesh = rockbake::readTriangleMesh(argv[1]);
    const double held = double(mesh.positions.capacity() * sizeof(mesh.positions[0]) +
                               mesh.triangles.capacity() * sizeof(mesh.triangles[0])) /
                        (1 << 20);
    std::printf("%zu vertices, %zu triangles: the mesh holds %.1f MiB; peak RSS %.1f MiB (%.1f MiB before reading)\n",
                mesh.positions.size(), mesh.triangles.size(), held, peakMiB(), before);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
