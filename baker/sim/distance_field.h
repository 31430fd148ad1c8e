// Signed distance to the boundary of a set of cells (SPEC §2.4 rind, §2.8
// variation), world units, negative inside. OpenVDB stays in the .cpp.
#pragma once

#include <cstdint>
#include <vector>

#include "core/voxel_rock.h"

namespace rockbake {

// `inside`: one flag per cell of `layout`. The boundary lies midway between
// inside and outside cell centres; cells beyond the grid's sides and top are
// outside, and with the ground each cell below z = 0 is what the cell above
// it is, so the ground adds no boundary. Exact within about a tenth of a voxel
// within `reach` (world units) of the boundary; beyond it ±reach.
// Deterministic at any thread count.
std::vector<float> signedDistance(const std::vector<std::uint8_t>& inside, const GridLayout& layout, double reach);

}  // namespace rockbake
