#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/alpha_pass_vertex.glsl"
// The SDF GI's alpha pass (gi::GiContext::alphaPassState) over GpuScene's vertex buffer: world-space triangles of
// alpha-tested materials as they are, with the material (as a float, exact below 2^24) and the texture
// coordinates for alpha_pass.frag; other triangles get a NaN position, which the pass's geometry stage drops, so
// that only the cards count in the alpha cache.
BL_READ_BUFFER(2) Materials { vec4 materials[]; };  // 4 per material; [4m + 3].x: the alpha cut-off (0: opaque)
layout(location = 0) in vec3 position;
layout(location = 2) in uint material;
layout(location = 4) in vec2 uv;
BL_ALPHA_VERTEX_OUTPUTS

void main() {
    bool alphaTested = materials[4u * material + 3u].x > 0.0;
    blAlphaVertex(alphaTested ? position : vec3(uintBitsToFloat(0x7FC00000u)), vec4(float(material), uv, 0.0));
}
