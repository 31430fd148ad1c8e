// The decimation response f (docs/model.md §5, paper Fig. 13): maps exposure in
// [0, 1] to a weathering factor in [0, 1].
#pragma once

#include <algorithm>
#include <cmath>

#include "preset/preset.h"

namespace rockbake {

inline double applyResponse(const ResponseParams& response, double x) {
  x = std::clamp(x, 0.0, 1.0);
  switch (response.kind) {
    case ResponseParams::Kind::Power:
      return std::pow(x, response.value);
    case ResponseParams::Kind::Threshold:
      return std::max(0.0, (x - response.value) / (1.0 - response.value));
    case ResponseParams::Kind::Curve: {
      const auto& c = response.curve;
      if (x <= c.front()[0]) return c.front()[1];
      for (std::size_t i = 1; i < c.size(); ++i)
        if (x <= c[i][0]) return c[i - 1][1] + (x - c[i - 1][0]) / (c[i][0] - c[i - 1][0]) * (c[i][1] - c[i - 1][1]);
      return c.back()[1];
    }
  }
  return x;
}

}  // namespace rockbake
