// Second-order (L2, 9 coefficients) real spherical harmonics of RGB radiance.
#ifndef BRICKLIGHT_GI_SH_GLSL
#define BRICKLIGHT_GI_SH_GLSL

struct GiSH {
    vec3 c[9];
};

void giShBasis(vec3 d, out float y[9]) {
    y[0] = 0.282095;
    y[1] = 0.488603 * d.y;
    y[2] = 0.488603 * d.z;
    y[3] = 0.488603 * d.x;
    y[4] = 1.092548 * d.x * d.y;
    y[5] = 1.092548 * d.y * d.z;
    y[6] = 0.315392 * (3.0 * d.z * d.z - 1.0);
    y[7] = 1.092548 * d.x * d.z;
    y[8] = 0.546274 * (d.x * d.x - d.y * d.y);
}

GiSH giShZero() {
    GiSH s;
    for (int i = 0; i < 9; ++i) s.c[i] = vec3(0.0);
    return s;
}

// Radiance SH convolved with a lobe of band weights (1, g1, g2) and evaluated along d.
vec3 giShEvaluate(GiSH s, vec3 d, float g1, float g2) {
    float y[9];
    giShBasis(d, y);
    vec3 r = s.c[0] * y[0];
    for (int i = 1; i < 4; ++i) r += s.c[i] * (y[i] * g1);
    for (int i = 4; i < 9; ++i) r += s.c[i] * (y[i] * g2);
    return r;
}

// Irradiance / pi for normal n (a white Lambertian surface's outgoing radiance): the clamped-cosine
// convolution (pi, 2pi/3, pi/4) divided by pi.
vec3 giShDiffuse(GiSH s, vec3 n) { return max(giShEvaluate(s, n, 2.0 / 3.0, 0.25), vec3(0.0)); }

// Radiance along d seen through a lobe of perceptual roughness r (the specular fallback): from the
// unfiltered signal at r = 0 to the cosine lobe at r = 1.
vec3 giShLobe(GiSH s, vec3 d, float r) { return max(giShEvaluate(s, d, mix(1.0, 2.0 / 3.0, r), mix(1.0, 0.25, r)), vec3(0.0)); }

GiSH giShMix(GiSH a, GiSH b, float t) {
    for (int i = 0; i < 9; ++i) a.c[i] = mix(a.c[i], b.c[i], t);
    return a;
}

#endif
