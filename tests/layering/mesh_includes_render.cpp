// Must not compile: the mesh stage comes before the render stage, so it cannot
// see render's headers (baker/CMakeLists.txt).
#include "render/scene.h"
