// A point or extent in world units (double precision), shared by every stage.
#pragma once

#include <array>

namespace rockbake {

using Vec3d = std::array<double, 3>;

}  // namespace rockbake
