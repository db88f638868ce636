// Shader compilation (at createShader) and program linking: one program per compute shader, one per
// (vertex, geometry, fragment) combination, linked at first use and cached (failures too, so a bad
// combination reports its log every time without relinking).
#pragma once

#include <array>
#include <map>
#include <string>

#include "gl_objects.h"

namespace bricklight::gl::detail {

GLenum shaderStageEnum(rhi::ShaderStage stage);
// 0 and the info log in *log on failure.
GLuint compileShader(const Functions& gl, GLenum stage, const char* source, std::string* log);
GLuint linkProgram(const Functions& gl, const GLuint* shaders, int count, std::string* log);
// Highest literal gl_ClipDistance[i] index written + 1 (GL needs GL_CLIP_DISTANCEi enabled; Vulkan not).
uint32_t countClipDistances(const char* glsl);

class ProgramCache {
public:
    // Shaders: vertex, geometry (may be null), fragment (may be null).
    GLuint get(const Functions& gl, const ShaderRecord* vs, const ShaderRecord* gs, const ShaderRecord* fs,
               std::string* log);
    void forget(const Functions& gl, uint32_t shaderId);
    void clear(const Functions& gl);

private:
    struct Entry {
        GLuint program = 0;
        std::string log;
    };
    std::map<std::array<uint32_t, 3>, Entry> programs_;
};

}  // namespace bricklight::gl::detail
