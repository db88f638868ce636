// Shared-exponent RGB (9-9-9-5) in a uint, for radiance and emission kept per brick or per cache texel.
// 0 is kept for "never written": black is stored as 1.
#ifndef BRICKLIGHT_RGB9E5_GLSL
#define BRICKLIGHT_RGB9E5_GLSL

uint blEncodeRgb9e5(vec3 c) {
    c = clamp(c, vec3(0.0), vec3(65408.0));
    float m = max(c.r, max(c.g, c.b));
    int e = max(-16, int(floor(log2(max(m, 1e-30))))) + 16;  // biased exponent (bias 15) + 1
    float scale = exp2(float(e - 24));
    if (floor(m / scale + 0.5) >= 512.0) {
        e += 1;
        scale *= 2.0;
    }
    uvec3 q = uvec3(min(floor(c / scale + 0.5), vec3(511.0)));
    uint bits = q.r | (q.g << 9) | (q.b << 18) | (uint(clamp(e, 0, 31)) << 27);
    return bits == 0u ? 1u : bits;
}

vec3 blDecodeRgb9e5(uint v) {
    float scale = exp2(float(int(v >> 27) - 24));
    return vec3(uvec3(v, v >> 9, v >> 18) & 511u) * scale;
}

#endif
