// Must not compile: the mesh stage does not link the simulation, so it cannot see its
// headers (baker/CMakeLists.txt); the simulation's results reach it as plain data.
#include "sim/weathering.h"
