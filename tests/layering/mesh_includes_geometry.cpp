// Must compile: the mesh stage links the mesh kernel (baker/CMakeLists.txt).
#include "geometry/edge_table.h"
