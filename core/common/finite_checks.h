// Checks of the numbers applications hand the techniques (transforms, cameras, bounds, directions): every
// element finite. Shared by every technique in core/.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace bricklight::detail {

inline bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}
inline bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

}  // namespace bricklight::detail
