// Five mips of the depth pyramid in one dispatch (core/gbuffer/depth_pyramid.cpp; included by depth_pyramid_first.comp,
// which reads the depth texture and writes mip 0 as well, and depth_pyramid_next.comp, which reads mip s). Each group
// takes a 32 × 32 tile of mip s and reduces it through shared memory to mips s + 1 .. s + 5 (16 × 16 down to 1 × 1);
// the last group of a row (column) also takes the columns (rows) past the last whole tile, so that a texel's
// footprint — 2 × 2 texels below, with a third column (row) under the last texel of a mip above an odd size — never
// spans two groups. One dispatch instead of one per mip: each dispatch waited for the one before, and the small
// mips' dispatches were mostly that wait. The first dispatch reads a 2 × 2 footprint of the depth with one gather.
layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Params {
    uvec4 size;  // xy mip s's extent; z the mips this dispatch writes after s (0..5); w unused
} params;
#ifdef DEPTH_PYRAMID_FIRST
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_IMAGE(0, rg32f) uniform writeonly image2D mip0;  // mip s = 0
#else
BL_IMAGE(0, rg32f) uniform readonly image2D source;  // mip s
#endif
// Mips s + 1 .. s + 5; past the end of the chain, a scratch texture's (never written).
BL_IMAGE(1, rg32f) uniform writeonly image2D mip1;
BL_IMAGE(2, rg32f) uniform writeonly image2D mip2;
BL_IMAGE(3, rg32f) uniform writeonly image2D mip3;
BL_IMAGE(4, rg32f) uniform writeonly image2D mip4;
BL_IMAGE(5, rg32f) uniform writeonly image2D mip5;

// One level's texels of the group's region, row by row: up to 31 × 31 at level 1 (a last group's), 15 × 15 at 2.
shared vec2 levelOdd[32 * 32], levelEven[16 * 16];

void storeLevel(uint level, ivec2 p, vec2 v) {
    vec4 t = vec4(v, 0.0, 0.0);
    if (level == 1u) imageStore(mip1, p, t);
    else if (level == 2u) imageStore(mip2, p, t);
    else if (level == 3u) imageStore(mip3, p, t);
    else if (level == 4u) imageStore(mip4, p, t);
    else imageStore(mip5, p, t);
}

vec2 loadSource(ivec2 p) {
#ifdef DEPTH_PYRAMID_FIRST
    float d = texelFetch(depthTexture, p, 0).r;
    imageStore(mip0, p, vec4(d, d, 0.0, 0.0));  // every texel lies under exactly one texel above: written once
    return vec2(d);
#else
    return imageLoad(source, p).rg;
#endif
}

void main() {
    uvec2 groups = gl_NumWorkGroups.xy, group = gl_WorkGroupID.xy;
    bvec2 lastGroup = equal(group, groups - 1u);
    uvec2 below = params.size.xy;  // the extent of the level below the one being built
    for (uint level = 1u; level <= 5u; ++level) {
        uvec2 extent = max(below >> 1u, uvec2(1u));
        // The group's texels of this level and of the one below (first texel, count).
        uvec2 tile = uvec2(32u >> level);
        uvec2 first = group * tile, firstBelow = group * tile * 2u;
        uvec2 count = mix(tile, extent - min(first, extent), lastGroup);
        uvec2 countBelow = mix(tile * 2u, below - min(firstBelow, below), lastGroup);
        // Level 1 also when no mip follows s (a 1 × 1 pyramid): its reads write mip 0.
        if (level <= max(params.size.z, 1u)) {
            for (uint i = gl_LocalInvocationID.x; i < count.x * count.y; i += 256u) {
                uvec2 local = uvec2(i % count.x, i / count.x), p = first + local;
                // The footprint: 2p .. 2p + 1, and 2p + 2 on the last texel above an odd size; clamped where a size
                // stopped halving at 1.
                uvec2 hi = min(2u * p + 1u + uvec2(equal(p, extent - 1u)) * (below & 1u), below - 1u);
                vec2 mm = vec2(1e30, -1e30);
                bool gathered = false;
#ifdef DEPTH_PYRAMID_FIRST
                if (level == 1u && all(equal(hi, 2u * p + 1u))) {
                    // A 2 × 2 footprint: one gather at the corner its four texels share (w: 2p, z: +x, x: +y, y: +x+y).
                    vec4 g = textureGather(depthTexture, vec2(2u * p + 1u) / vec2(params.size.xy), 0);
                    ivec2 q = ivec2(2u * p);
                    imageStore(mip0, q, g.wwww);
                    imageStore(mip0, q + ivec2(1, 0), g.zzzz);
                    imageStore(mip0, q + ivec2(0, 1), g.xxxx);
                    imageStore(mip0, q + ivec2(1, 1), g.yyyy);
                    mm = vec2(min(min(g.x, g.y), min(g.z, g.w)), max(max(g.x, g.y), max(g.z, g.w)));
                    gathered = true;
                }
#endif
                for (uint y = 2u * p.y; !gathered && y <= hi.y; ++y)
                    for (uint x = 2u * p.x; x <= hi.x; ++x) {
                        vec2 t;
                        if (level == 1u) {
                            t = loadSource(ivec2(x, y));
                        } else {
                            uint at = (y - firstBelow.y) * countBelow.x + (x - firstBelow.x);
                            t = (level & 1u) == 0u ? levelOdd[at] : levelEven[at];
                        }
                        mm = vec2(min(mm.x, t.x), max(mm.y, t.y));
                    }
                if ((level & 1u) == 1u) levelOdd[i] = mm;
                else levelEven[i] = mm;
                if (level <= params.size.z) storeLevel(level, ivec2(p), mm);
            }
        }
        barrier();
        below = extent;
    }
}
