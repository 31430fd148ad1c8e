// Must compile: the mesh stage comes after the simulation.
#include "sim/weathering.h"
