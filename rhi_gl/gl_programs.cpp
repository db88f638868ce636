#include "gl_programs.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace bricklight::gl::detail {

GLenum shaderStageEnum(rhi::ShaderStage stage) {
    switch (stage) {
        case rhi::ShaderStage::Compute: return GL_COMPUTE_SHADER;
        case rhi::ShaderStage::Vertex: return GL_VERTEX_SHADER;
        case rhi::ShaderStage::Geometry: return GL_GEOMETRY_SHADER;
        case rhi::ShaderStage::Fragment: return GL_FRAGMENT_SHADER;
    }
    return 0;
}

GLuint compileShader(const Functions& gl, GLenum stage, const char* source, std::string* log) {
    GLuint shader = gl.CreateShader(stage);
    if (!shader) {
        *log = "glCreateShader failed";
        return 0;
    }
    gl.ShaderSource(shader, 1, &source, nullptr);
    gl.CompileShader(shader);
    GLint ok = GL_FALSE, length = 0;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok) return shader;
    gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    log->assign(length > 1 ? size_t(length) : 1, '\0');
    gl.GetShaderInfoLog(shader, length, nullptr, log->data());
    log->resize(strlen(log->c_str()));
    gl.DeleteShader(shader);
    return 0;
}

GLuint linkProgram(const Functions& gl, const GLuint* shaders, int count, std::string* log) {
    GLuint program = gl.CreateProgram();
    for (int i = 0; i < count; ++i) gl.AttachShader(program, shaders[i]);
    gl.LinkProgram(program);
    for (int i = 0; i < count; ++i) gl.DetachShader(program, shaders[i]);
    GLint ok = GL_FALSE, length = 0;
    gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok) return program;
    gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    log->assign(length > 1 ? size_t(length) : 1, '\0');
    gl.GetProgramInfoLog(program, length, nullptr, log->data());
    log->resize(strlen(log->c_str()));
    gl.DeleteProgram(program);
    return 0;
}

uint32_t countClipDistances(const char* glsl) {
    uint32_t count = 0;
    const char* needle = "gl_ClipDistance[";
    for (const char* p = strstr(glsl, needle); p; p = strstr(p + 1, needle)) {
        char* end = nullptr;
        long index = strtol(p + strlen(needle), &end, 10);
        if (end != p + strlen(needle) && *end == ']' && index >= 0 && index < 8)
            count = std::max<uint32_t>(count, uint32_t(index) + 1);
    }
    return count;
}

GLuint ProgramCache::get(const Functions& gl, const ShaderRecord* vs, const ShaderRecord* gs, const ShaderRecord* fs,
                         std::string* log) {
    std::array<uint32_t, 3> key{vs->id, gs ? gs->id : 0u, fs ? fs->id : 0u};
    auto it = programs_.find(key);
    if (it == programs_.end()) {
        GLuint shaders[3];
        int n = 0;
        for (const ShaderRecord* s : {vs, gs, fs})
            if (s) shaders[n++] = s->shader;
        Entry e;
        e.program = linkProgram(gl, shaders, n, &e.log);
        if (e.program) {
            std::string label = vs->name + (gs ? "+" + gs->name : "") + (fs ? "+" + fs->name : "");
            gl.ObjectLabel(GL_PROGRAM, e.program, -1, label.c_str());
        }
        it = programs_.emplace(key, std::move(e)).first;
    }
    *log = it->second.log;
    return it->second.program;
}

void ProgramCache::forget(const Functions& gl, uint32_t shaderId) {
    for (auto it = programs_.begin(); it != programs_.end();) {
        const auto& k = it->first;
        if (k[0] == shaderId || k[1] == shaderId || k[2] == shaderId) {
            if (it->second.program) gl.DeleteProgram(it->second.program);
            it = programs_.erase(it);
        } else {
            ++it;
        }
    }
}

void ProgramCache::clear(const Functions& gl) {
    for (auto& [k, e] : programs_)
        if (e.program) gl.DeleteProgram(e.program);
    programs_.clear();
}

}  // namespace bricklight::gl::detail
