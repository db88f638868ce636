// IEEE binary16 -> float, for reading back RGBA16_FLOAT / RG16_FLOAT / R16_FLOAT resources on the CPU
// (tests, tools, the GI cache read-back).
#pragma once

#include <cmath>
#include <cstdint>

namespace bricklight {

inline float halfToFloat(uint16_t h) {
    const uint32_t e = (h >> 10) & 0x1Fu, m = h & 0x3FFu;
    const float f = e == 0 ? std::ldexp(float(m), -24) : e == 31 ? (m ? NAN : INFINITY) : std::ldexp(float(m | 0x400u), int(e) - 25);
    return (h & 0x8000u) ? -f : f;
}

}  // namespace bricklight
