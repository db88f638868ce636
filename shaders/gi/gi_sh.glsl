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

// The basis along d times a lobe's band weights (1, g1, g2): radiance SH convolved with the lobe and
// evaluated along d is the dot product of its coefficients with these (linear in the SH, so a sum of
// weighted SH can be evaluated term by term).
void giShWeights(vec3 d, float g1, float g2, out float w[9]) {
    giShBasis(d, w);
    for (int i = 1; i < 4; ++i) w[i] *= g1;
    for (int i = 4; i < 9; ++i) w[i] *= g2;
}

// Irradiance / pi for normal n (a white Lambertian surface's outgoing radiance): the clamped-cosine
// convolution (pi, 2pi/3, pi/4) divided by pi.
void giShDiffuseWeights(vec3 n, out float w[9]) { giShWeights(n, 2.0 / 3.0, 0.25, w); }

// Radiance along d seen through a lobe of perceptual roughness r (the specular fallback): from the
// unfiltered signal at r = 0 to the cosine lobe at r = 1.
void giShLobeWeights(vec3 d, float r, out float w[9]) { giShWeights(d, mix(1.0, 2.0 / 3.0, r), mix(1.0, 0.25, r), w); }

vec3 giShDot(GiSH s, float w[9]) {
    vec3 r = vec3(0.0);
    for (int i = 0; i < 9; ++i) r += s.c[i] * w[i];
    return r;
}

vec3 giShDiffuse(GiSH s, vec3 n) {
    float w[9];
    giShDiffuseWeights(n, w);
    return max(giShDot(s, w), vec3(0.0));
}

GiSH giShMix(GiSH a, GiSH b, float t) {
    for (int i = 0; i < 9; ++i) a.c[i] = mix(a.c[i], b.c[i], t);
    return a;
}

#endif
