// Shared-exponent RGB (9-9-9-5) in a uint, for radiance and emission kept per brick or per cache texel, and for
// volumes written through an R32_UINT storage image and sampled through an RGB9E5_FLOAT view (the layout Vulkan's
// E5B9G9R9_UFLOAT_PACK32 and GL's RGB9_E5 share: red in bits 0–8, green 9–17, blue 18–26, exponent 27–31).
#ifndef BRICKLIGHT_RGB9E5_GLSL
#define BRICKLIGHT_RGB9E5_GLSL

// Negative channels are 0, values past the largest (65408) that; a value whose mantissas all round to 0 keeps its
// exponent bits. Canonical: the exponent is the smallest that holds the largest channel, so a word with a non-zero
// exponent has a largest mantissa of 256 or more, on every device (log2 may round either way near a power of two;
// both corrections below undo that) — vct_layout.glsl's light entries rely on it.
uint blRgb9e5Bits(vec3 c) {
    c = clamp(c, vec3(0.0), vec3(65408.0));
    float m = max(c.r, max(c.g, c.b));
    int e = max(-16, int(floor(log2(max(m, 1e-30))))) + 16;  // biased exponent (bias 15) + 1
    float scale = exp2(float(e - 24));
    if (e > 0 && floor(m / scale + 0.5) < 256.0) {
        e -= 1;
        scale *= 0.5;
    }
    if (floor(m / scale + 0.5) >= 512.0) {
        e += 1;
        scale *= 2.0;
    }
    uvec3 q = uvec3(min(floor(c / scale + 0.5), vec3(511.0)));
    return q.r | (q.g << 9) | (q.b << 18) | (uint(clamp(e, 0, 31)) << 27);
}

// Black (every mantissa 0) is 0.
uint blPackRgb9e5(vec3 c) {
    uint bits = blRgb9e5Bits(c);
    return (bits & 0x7FFFFFFu) == 0u ? 0u : bits;
}

// 0 is kept for "never written": black is stored as 1.
uint blEncodeRgb9e5(vec3 c) {
    uint bits = blRgb9e5Bits(c);
    return bits == 0u ? 1u : bits;
}

vec3 blDecodeRgb9e5(uint v) {
    float scale = exp2(float(int(v >> 27) - 24));
    return vec3(uvec3(v, v >> 9, v >> 18) & 511u) * scale;
}

#endif
