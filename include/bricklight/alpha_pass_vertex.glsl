// The vertex shader an application writes for the GI's alpha pass (gi::GiContext::alphaPassState): it declares
// BL_ALPHA_VERTEX_OUTPUTS and calls blAlphaVertex once with the vertex in world space and one vector of its own
// (texture coordinates, a material index...), which reaches blAlphaPresent (bricklight/alpha_pass.glsl)
// interpolated over the triangle. Our geometry shader projects each triangle into every cascade of the field.
#ifndef BRICKLIGHT_ALPHA_PASS_VERTEX_GLSL
#define BRICKLIGHT_ALPHA_PASS_VERTEX_GLSL

#define BL_ALPHA_VERTEX_OUTPUTS layout(location = 0) out vec4 blAlphaUserOut;

#define blAlphaVertex(worldPosition, user)           \
    do {                                             \
        gl_Position = vec4((worldPosition), 1.0);    \
        blAlphaUserOut = (user);                     \
    } while (false)

#endif
