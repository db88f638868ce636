#ifndef GI_LIGHTS_GLSL
#define GI_LIGHTS_GLSL
// The application's lights (DispatchDesc::lights), shadowed through the distance field: what relighting adds at
// a texel besides its rays. Needs the lights buffer declared as `giLights` (4 vec4 per light: core/gi/gi_constants.h,
// GpuLight) and giTraceThroughAlpha (gi_alpha.glsl).
// gi::LightType as the record's position.w: Directional 0, Point 1, Spot 2, Rect 3, Triangle 4.
#define GI_LIGHT_DIRECTIONAL 0.0
#define GI_LIGHT_SPOT 2.0
#define GI_LIGHT_RECT 3.0

// Whether the segment from p along unit l reaches `distance` without meeting a surface. A segment that ends on
// an emitting surface (an area light's point) meets that surface itself: a hit within `endSlack` of its end
// counts as reaching it. No answer (out of iterations): in shadow, the safer guess (no light from nowhere).
bool giLit(vec3 p, vec3 l, float distance, float endSlack, inout uint rng) {
    BlSdfHit hit = giTraceThroughAlpha(giMakeRay(p, l, min(distance, giFrame.trace.w), GI_RAY_SHADOW), rng);
    if (hit.gaveUp) return false;
    if (!hit.hit) return true;
    return endSlack > 0.0 && hit.t >= distance - endSlack * blSdfTable.cascades[hit.cascade].voxelSize.x;
}

// Irradiance from the frame's lights first, first + stride, ... at p (normal n). An area light gives one sample
// (a point drawn uniformly on it): irradiance L · A · cosθ_light · cosθ_surface / d², unbiased, and averaged by
// the cache's blend over frames.
vec3 giLightIrradiance(vec3 p, vec3 n, uint first, uint stride) {
    uint rng = giPcg(floatBitsToUint(p.x) ^ giPcg(floatBitsToUint(p.y) ^ giPcg(floatBitsToUint(p.z) ^ giFrameIndex())));
    vec3 sum = vec3(0.0);
    for (uint i = first; i < giFrame.relight.x; i += stride) {
        vec4 a = giLights[4u * i], b = giLights[4u * i + 1u], c = giLights[4u * i + 2u], e = giLights[4u * i + 3u];
        vec3 l = b.xyz, irradiance = c.rgb;
        float distance = 1e30, endSlack = 0.0;
        if (a.w > GI_LIGHT_SPOT + 0.5) {  // rect or triangle: corner a.xyz, edges b.xyz and e.xyz, area e.w
            vec2 u = vec2(giRandom(rng), giRandom(rng));
            if (a.w > GI_LIGHT_RECT + 0.5 && u.x + u.y > 1.0) u = 1.0 - u;  // the triangle's half of the parallelogram
            vec3 toLight = a.xyz + u.x * b.xyz + u.y * e.xyz - p;
            float d2 = max(dot(toLight, toLight), 1e-8);
            distance = sqrt(d2);
            l = toLight / distance;
            float facing = -dot(normalize(cross(b.xyz, e.xyz)), l);
            if (b.w > 0.5) facing = abs(facing);  // two-sided
            irradiance *= max(facing, 0.0) * e.w / d2;
            endSlack = 1.0;
        } else if (a.w > GI_LIGHT_DIRECTIONAL + 0.5) {  // point or spot
            vec3 toLight = a.xyz - p;
            float d2 = max(dot(toLight, toLight), 1e-8);
            distance = sqrt(d2);
            l = toLight / distance;
            irradiance /= d2;
            if (a.w > GI_LIGHT_SPOT - 0.5) {  // spot: c.w = cos(outer) < b.w = cos(inner)
                float axis = dot(-l, b.xyz);
                irradiance *= b.w > c.w ? smoothstep(c.w, b.w, axis) : step(c.w, axis);
            }
        }
        float cosine = dot(n, l);
        if (cosine <= 0.0 || all(equal(irradiance, vec3(0.0)))) continue;
        if (giLit(p, l, distance, endSlack, rng)) sum += irradiance * cosine;
    }
    return sum;
}
#endif
