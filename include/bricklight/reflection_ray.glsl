// A pixel's reflection ray for hybrid reflections: the GGX lobe's direction sampled from the visible normals
// (Heitz 2018) with random numbers hashed from the pixel and the frame index. The screen-space trace
// (reflections::ReflectionClassifier) and the distance-field trace (gi::GiContext::traceReflectionRays) both call it,
// so that a ray the screen gave up on continues in the field as the same ray. Self-contained: no bindings.
#ifndef BRICKLIGHT_REFLECTION_RAY_GLSL
#define BRICKLIGHT_REFLECTION_RAY_GLSL

uint blReflectionRayHash(uint v) {  // PCG
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Two numbers in [0, 1) for a pixel and frame.
vec2 blReflectionRayRandom(uvec2 pixel, uint frameIndex) {
    uint h = blReflectionRayHash(blReflectionRayHash(pixel.x * 0x8da6b343u ^ pixel.y * 0xd8163841u) ^ (frameIndex * 0x9e3779b9u));
    uint h2 = blReflectionRayHash(h);
    return vec2(float(h >> 8), float(h2 >> 8)) / 16777216.0;
}

// An orthonormal basis around unit n (Duff et al. 2017).
void blReflectionRayBasis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// The reflection direction of a surface with unit normal n (facing the eye) and perceptual roughness r, seen
// along unit `toEye` (surface to camera). GGX α = r² (below 1e-4, a mirror). Never below the surface.
vec3 blReflectionDirection(uvec2 pixel, uint frameIndex, vec3 n, vec3 toEye, float roughness) {
    float alpha = roughness * roughness;
    if (alpha < 1e-4) return normalize(reflect(-toEye, n));  // a mirror: its own direction, no sampling noise
    vec3 t, b;
    blReflectionRayBasis(n, t, b);
    vec3 v = normalize(vec3(dot(toEye, t), dot(toEye, b), max(dot(toEye, n), 1e-4)));
    vec2 u = blReflectionRayRandom(pixel, frameIndex);
    // The visible normal, sampled in the hemisphere configuration of the stretched view vector.
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float radius = sqrt(u.x), phi = 6.28318530718 * u.y;
    float p1 = radius * cos(phi), p2 = radius * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    vec3 h = normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
    vec3 l = reflect(-v, h);
    if (l.z <= 0.0) l = reflect(-v, vec3(0.0, 0.0, 1.0));  // a sample below the surface: the mirror direction
    return normalize(t * l.x + b * l.y + n * l.z);
}

#endif
