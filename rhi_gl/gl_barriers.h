// glMemoryBarrier chosen for the next consumer (the sokol / Diligent pending-bits pattern).
//
// Only shader writes (SSBO stores, image stores/atomics) are incoherent in GL; API writes (BufferSubData,
// copies, clears, framebuffer writes) are ordered by GL itself. So each resource remembers the serial of
// its last incoherent write, and the tracker remembers, per barrier bit, the latest write serial that an
// issued glMemoryBarrier with that bit made visible. A consumer that reaches a resource through path B
// needs bit B iff the resource's last write is newer than the last barrier with B. Since glMemoryBarrier
// is global, one issued bit covers every resource written so far: read-after-read and repeated reads
// after one barrier cost nothing.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

#include "gl_functions.h"

namespace bricklight::gl::detail {

class BarrierTracker {
public:
    // Whether a consumer using path `bit` on a resource last shader-written at `lastWrite` needs `bit`.
    bool needs(uint64_t lastWrite, GLbitfield bit) const {
        return lastWrite != 0 && lastWrite > issued_[std::countr_zero(bit)];
    }
    // Accumulates into *bits what a consumer needs.
    void require(GLbitfield* bits, uint64_t lastWrite, GLbitfield bit) const {
        if (needs(lastWrite, bit)) *bits |= bit;
    }
    // Issues the barrier (if any bits) and records which writes it covered.
    void issue(const Functions& gl, GLbitfield bits) {
        if (!bits) return;
        gl.MemoryBarrier(bits);
        ++count_;
        for (GLbitfield b = bits; b; b &= b - 1) issued_[std::countr_zero(b)] = serial_;
    }
    // Serial for the incoherent writes of the call just issued; store it in each written resource.
    uint64_t nextWriteSerial() { return ++serial_; }
    uint64_t count() const { return count_; }

private:
    uint64_t serial_ = 0;
    uint64_t count_ = 0;
    std::array<uint64_t, 32> issued_{};
};

}  // namespace bricklight::gl::detail
