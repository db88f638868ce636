// Checks of the matrices applications hand the techniques (transforms, cameras): every element finite.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace bricklight::detail {

inline bool finiteMatrix(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

}  // namespace bricklight::detail
