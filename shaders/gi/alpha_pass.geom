#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The GI's alpha pass, geometry stage (gi::GiContext::alphaPassState): one invocation per cascade of the
// distance field projects the triangle along its dominant axis into that cascade's 64³ voxels, at
// BL_ALPHA_PIXELS_PER_CELL pixels per 4³ cell of a brick; the application's fragment shader (through
// bricklight/alpha_pass.glsl) counts each fragment in the cell it lands in. The world position goes along, so
// that the fragment needs no unprojection. Plain rasterization: a triangle smaller than a pixel may leave no
// fragment, which leaves its cells' coverage unknown (traced as opaque), never wrong.
#define BL_ALPHA_PASS_GEOMETRY
#include "bricklight/alpha_pass.glsl"
layout(triangles, invocations = 16) in;
layout(triangle_strip, max_vertices = 3) out;

layout(location = 0) in vec4 blAlphaUserIn[];
layout(location = 0) out vec4 blAlphaUserGs;
layout(location = 1) out vec3 blAlphaWorldGs;
layout(location = 2) flat out uint blAlphaCascadeGs;

void main() {
    uint cascade = uint(gl_InvocationID);
    if (cascade >= blSdfTable.header.x) return;
    BlSdfCascade info = blSdfTable.cascades[cascade];
    if (info.origin.w == 0) return;
    vec3 world[3], local[3];
    for (int i = 0; i < 3; ++i) {
        world[i] = gl_in[i].gl_Position.xyz;
        if (any(isnan(world[i])) || any(isinf(world[i]))) return;
        local[i] = world[i] * info.voxelSize.y - vec3(info.origin.xyz);
    }
    vec3 lo = min(min(local[0], local[1]), local[2]), hi = max(max(local[0], local[1]), local[2]);
    if (any(greaterThan(lo, vec3(64.0))) || any(lessThan(hi, vec3(0.0)))) return;
    vec3 n = abs(cross(local[1] - local[0], local[2] - local[0]));
    if (max(n.x, max(n.y, n.z)) == 0.0) return;
    int axis = n.x >= n.y && n.x >= n.z ? 0 : (n.y >= n.z ? 1 : 2);
    for (int i = 0; i < 3; ++i) {
        vec2 q = axis == 0 ? local[i].yz : (axis == 1 ? local[i].zx : local[i].xy);
        gl_Position = vec4(q / 64.0 * 2.0 - 1.0, 0.5, 1.0);
        blAlphaUserGs = blAlphaUserIn[i];
        blAlphaWorldGs = world[i];
        blAlphaCascadeGs = cascade;
        EmitVertex();
    }
    EndPrimitive();
}
