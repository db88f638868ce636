// The specular ray of a pixel: a GGX reflection direction sampled from the visible normals (Heitz 2018)
// for the pixel's perceptual roughness, with a per-frame random number so that rays change over time.
#ifndef BRICKLIGHT_GI_SPECULAR_GLSL
#define BRICKLIGHT_GI_SPECULAR_GLSL

vec3 giSampleGgxVisibleNormal(vec3 v, float alpha, vec2 u) {  // v in the tangent frame (z = normal)
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = 2.0 * GI_PI * u.y;
    float a = r * cos(phi);
    float b = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    b = (1.0 - s) * sqrt(max(1.0 - a * a, 0.0)) + s * b;
    vec3 nh = a * t1 + b * t2 + sqrt(max(0.0, 1.0 - a * a - b * b)) * vh;
    return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
}

// Reflection direction for a surface (n, perceptual roughness) seen from `toEye` (unit); `u` random.
vec3 giSpecularDirection(vec3 n, vec3 toEye, float roughness, vec2 u) {
    vec3 t, b;
    giBasis(n, t, b);
    vec3 v = vec3(dot(toEye, t), dot(toEye, b), max(dot(toEye, n), 1e-4));
    float alpha = max(roughness * roughness, 1e-3);
    vec3 h = giSampleGgxVisibleNormal(normalize(v), alpha, u);
    vec3 l = reflect(-normalize(v), h);
    if (l.z <= 0.0) l = reflect(-normalize(v), vec3(0.0, 0.0, 1.0));
    return normalize(t * l.x + b * l.y + n * l.z);
}

#endif
