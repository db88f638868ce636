// The reflection ray of a pixel, shared by the screen-space trace (trace_reflections_screen.comp) and the SDF pass
// so that both halves of hybrid reflections trace the same ray. Needs blReflectionHash3 and blReflectionUnit
// (reflection_params.glsl) — or include this after any file that defines them.
//
//   pixel, frameIndex  seed the sample (the same pixel and frame give the same ray on every backend)
//   worldPosition      the surface point (the ray's origin; each tracer adds its own offset)
//   normal             unit world normal
//   toViewer           unit vector from the surface to the eye
//   alpha              GGX α = perceptual roughness²; below 1e-4 the mirror direction is taken
//
// Rough surfaces sample the GGX distribution of visible normals (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals") and reflect the view about the sampled normal; a sample that would leave below the surface
// falls back to the mirror direction.
#ifndef BRICKLIGHT_CLASSIFY_REFLECTION_RAY_GLSL
#define BRICKLIGHT_CLASSIFY_REFLECTION_RAY_GLSL

struct BlReflectionRay {
    vec3 origin;
    vec3 direction;  // unit
};

vec3 blSampleGgxVisibleNormal(vec3 viewLocal, float alpha, vec2 u) {
    vec3 stretched = normalize(vec3(alpha * viewLocal.xy, viewLocal.z));
    float lengthSq = dot(stretched.xy, stretched.xy);
    vec3 t1 = lengthSq > 0.0 ? vec3(-stretched.y, stretched.x, 0.0) * inversesqrt(lengthSq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(stretched, t1);
    float r = sqrt(u.x), phi = 6.28318530718 * u.y;
    float p1 = r * cos(phi), p2 = r * sin(phi);
    float s = 0.5 * (1.0 + stretched.z);
    p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * p2;
    vec3 h = p1 * t1 + p2 * t2 + sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0)) * stretched;
    return normalize(vec3(alpha * h.xy, max(h.z, 0.0)));
}

BlReflectionRay blReflectionRay(uvec2 pixel, uint frameIndex, vec3 worldPosition, vec3 normal, vec3 toViewer, float alpha) {
    vec3 mirror = reflect(-toViewer, normal);
    // A tangent frame around the normal (Frisvad's, with the branch-free sign of Duff et al.).
    float sgn = normal.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + normal.z), b = normal.x * normal.y * a;
    vec3 tangent = vec3(1.0 + sgn * normal.x * normal.x * a, sgn * b, -sgn * normal.x);
    vec3 bitangent = vec3(b, sgn + normal.y * normal.y * a, -normal.y);
    vec3 viewLocal = vec3(dot(toViewer, tangent), dot(toViewer, bitangent), dot(toViewer, normal));
    uint h = blReflectionHash3(uvec3(pixel, frameIndex));
    vec2 u = vec2(blReflectionUnit(h), blReflectionUnit(blReflectionHash(h)));
    vec3 m = blSampleGgxVisibleNormal(viewLocal, max(alpha, 1.0e-4), u);
    vec3 microNormal = m.x * tangent + m.y * bitangent + m.z * normal;
    vec3 sampled = reflect(-toViewer, microNormal);
    bool useSample = alpha >= 1.0e-4 && dot(sampled, normal) > 1.0e-4;
    BlReflectionRay ray;
    ray.origin = worldPosition;
    ray.direction = normalize(useSample ? sampled : mirror);
    return ray;
}

#endif
