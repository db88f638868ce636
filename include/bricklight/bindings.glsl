// Bricklight binding convention: one macro per binding class. The same source compiles to SPIR-V for
// Vulkan (descriptor set 0, one binding range per class) and to GLSL for OpenGL (one binding namespace
// per class). tools/shader_compiler checks every binding against this table; docs/rhi.md documents it.
//
//   class            GLSL                           Vulkan set 0 binding    OpenGL binding point
//   constants        BL_CONSTANTS(s) uniform B {}   0  + s (s < 4)          uniform buffer s
//   texture          BL_TEXTURE(s) uniform sampler  16 + s (s < 16)         texture unit s
//   read buffer      BL_READ_BUFFER(s) B {}         32 + s (s < 8)          shader storage s
//   storage buffer   BL_STORAGE_BUFFER(s) B {}      48 + s (s < 8)          shader storage 8 + s
//   storage image    BL_IMAGE(s, fmt) uniform image 64 + s (s < 8)          image unit s
#ifndef BRICKLIGHT_BINDINGS_GLSL
#define BRICKLIGHT_BINDINGS_GLSL

#ifdef VULKAN
#define BL_CONSTANTS(s) layout(std140, set = 0, binding = (0 + (s)))
#define BL_TEXTURE(s) layout(set = 0, binding = (16 + (s)))
#define BL_READ_BUFFER(s) layout(std430, set = 0, binding = (32 + (s))) readonly buffer
#define BL_STORAGE_BUFFER(s) layout(std430, set = 0, binding = (48 + (s))) buffer
#define BL_IMAGE(s, fmt) layout(set = 0, binding = (64 + (s)), fmt)
#else
#define BL_CONSTANTS(s) layout(std140, binding = (s))
#define BL_TEXTURE(s) layout(binding = (s))
#define BL_READ_BUFFER(s) layout(std430, binding = (s)) readonly buffer
#define BL_STORAGE_BUFFER(s) layout(std430, binding = (8 + (s))) buffer
#define BL_IMAGE(s, fmt) layout(binding = (s), fmt)
#endif

// Built-ins whose names differ between the two targets. BL_INSTANCE_INDEX includes firstInstance on Vulkan
// but not on OpenGL (gl_InstanceID): use per-instance vertex attributes, which honour it on both.
#ifdef VULKAN
#define BL_VERTEX_INDEX gl_VertexIndex
#define BL_INSTANCE_INDEX gl_InstanceIndex
#else
#define BL_VERTEX_INDEX gl_VertexID
#define BL_INSTANCE_INDEX gl_InstanceID
#endif

#endif
