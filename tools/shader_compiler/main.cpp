// bricklight-shaderc: compiles one GLSL 4.50 shader at build time into a C++ source that embeds
//   - SPIR-V for Vulkan (glslang, VULKAN defined),
//   - preprocessed GLSL for OpenGL (includes resolved, VULKAN undefined), itself compiled once here for
//     OpenGL so that a GL-only error fails the build, not the run,
//   - reflection (bindings per class and slot, image formats, block sizes, local size, vertex inputs,
//     fragment outputs), checked against the binding convention of bricklight/bindings.glsl and checked
//     to agree between the Vulkan and the OpenGL variants.
// Usage: bricklight-shaderc <name> <source.glsl> <out.cpp> <depfile> -I<dir>...
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/optimizer.hpp>

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

// Must match rhi::BindingClass, rhi::Format and the ranges in bindings.glsl.
enum BindingClass { kConstants = 0, kTexture, kReadBuffer, kStorageBuffer, kStorageImage };
const char* kClassNames[] = {"constants", "texture", "read buffer", "storage buffer", "storage image"};
struct ClassRange {
    int vulkanBase, glBase, slots;
};
const ClassRange kRanges[] = {{0, 0, 4}, {16, 0, 16}, {32, 0, 8}, {48, 8, 8}, {64, 0, 8}};

std::string readFile(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return {};
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

class Includer : public glslang::TShader::Includer {
public:
    explicit Includer(std::vector<std::string> dirs) : dirs_(std::move(dirs)) {}
    std::set<std::string> files;

    IncludeResult* includeLocal(const char* header, const char* includer, size_t depth) override {
        std::string inc = includer ? includer : "";
        auto slash = inc.find_last_of('/');
        std::string dir = slash == std::string::npos ? "." : inc.substr(0, slash);
        if (auto* r = tryOpen(dir + "/" + header)) return r;
        return includeSystem(header, includer, depth);
    }
    IncludeResult* includeSystem(const char* header, const char*, size_t) override {
        for (const auto& d : dirs_)
            if (auto* r = tryOpen(d + "/" + header)) return r;
        return nullptr;
    }
    void releaseInclude(IncludeResult* r) override {
        if (!r) return;
        delete static_cast<std::string*>(r->userData);
        delete r;
    }

private:
    IncludeResult* tryOpen(const std::string& path) {
        std::ifstream f(path, std::ios::binary);
        if (!f) return nullptr;
        auto* text = new std::string(readFile(path));
        files.insert(path);
        return new IncludeResult(path, text->data(), text->size(), text);
    }
    std::vector<std::string> dirs_;
};

EShLanguage stageOf(const std::string& path, const char** stageName) {
    auto ends = [&](const char* s) {
        std::string e = s;
        return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
    };
    if (ends(".comp")) return *stageName = "Compute", EShLangCompute;
    if (ends(".vert")) return *stageName = "Vertex", EShLangVertex;
    if (ends(".geom")) return *stageName = "Geometry", EShLangGeometry;
    if (ends(".frag")) return *stageName = "Fragment", EShLangFragment;
    *stageName = nullptr;
    return EShLangCount;
}

const char* formatOf(glslang::TLayoutFormat f) {
    using namespace glslang;
    switch (f) {
        case ElfR8: return "R8_UNORM";
        case ElfR8ui: return "R8_UINT";
        case ElfR16f: return "R16_FLOAT";
        case ElfR16ui: return "R16_UINT";
        case ElfR32f: return "R32_FLOAT";
        case ElfR32ui: return "R32_UINT";
        case ElfR32i: return "R32_SINT";
        case ElfRg8: return "RG8_UNORM";
        case ElfRg16f: return "RG16_FLOAT";
        case ElfRg32f: return "RG32_FLOAT";
        case ElfRg32ui: return "RG32_UINT";
        case ElfRgba8: return "RGBA8_UNORM";
        case ElfRgba16f: return "RGBA16_FLOAT";
        case ElfRgba32f: return "RGBA32_FLOAT";
        case ElfRgba32ui: return "RGBA32_UINT";
        case ElfR11fG11fB10f: return "R11G11B10_FLOAT";
        case ElfNone: return "Unknown";
        default: return nullptr;
    }
}

struct Binding {
    std::string name;
    int cls = 0, slot = 0;
    std::string dimension = "None", scalar = "None", format = "Unknown";
    bool readOnly = false, writeOnly = false, shadow = false;
    unsigned blockSize = 0, arrayStride = 0;
};

struct Reflection {
    std::vector<Binding> bindings;
    unsigned localSize[3] = {0, 0, 0};
    struct Input {
        std::string name;
        int location, components;
        std::string scalar;
    };
    std::vector<Input> inputs;
    unsigned colorOutputMask = 0;
    unsigned declaredSlots[5] = {};  // per class, bit = slot declared in the source (used or not)
};

const char* scalarOf(glslang::TBasicType t) {
    switch (t) {
        case glslang::EbtFloat: return "Float";
        case glslang::EbtUint: return "Uint";
        case glslang::EbtInt: return "Sint";
        default: return "None";
    }
}

// Classifies one reflected binding by its binding number under the given variant's convention.
bool classify(int binding, bool vulkan, bool isBuffer, bool isUniformBlock, bool isImage, bool readonly,
              int* cls, int* slot) {
    if (isUniformBlock) *cls = kConstants;
    else if (isBuffer) *cls = readonly ? kReadBuffer : kStorageBuffer;
    else if (isImage) *cls = kStorageImage;
    else *cls = kTexture;
    const ClassRange& r = kRanges[*cls];
    int base = vulkan ? r.vulkanBase : r.glBase;
    *slot = binding - base;
    return *slot >= 0 && *slot < r.slots;
}

bool reflect(glslang::TProgram& program, EShLanguage stage, bool vulkan, const std::string& name,
             Reflection* out) {
    using namespace glslang;
    program.buildReflection(EShReflectionDefault | EShReflectionSeparateBuffers |
                            EShReflectionAllBlockVariables | EShReflectionUnwrapIOBlocks);
    bool ok = true;
    auto fail = [&](const std::string& what) {
        fprintf(stderr, "%s: %s\n", name.c_str(), what.c_str());
        ok = false;
    };
    for (int i = 0; i < program.getNumUniformBlocks(); ++i) {
        const TObjectReflection& b = program.getUniformBlock(i);
        Binding r;
        r.name = b.name;
        if (!classify(b.getBinding(), vulkan, false, true, false, false, &r.cls, &r.slot))
            fail("uniform block '" + r.name + "' binding " + std::to_string(b.getBinding()) +
                 " is outside BL_CONSTANTS' range");
        r.blockSize = b.size;
        if (r.blockSize > 256) fail("uniform block '" + r.name + "' is larger than 256 bytes (kMaxConstantsBytes)");
        out->bindings.push_back(r);
    }
    for (int i = 0; i < program.getNumBufferBlocks(); ++i) {
        const TObjectReflection& b = program.getBufferBlock(i);
        const TType* type = b.getType();
        bool readonly = type && type->getQualifier().isReadOnly();
        Binding r;
        r.name = b.name;
        r.dimension = "Buffer";
        r.readOnly = readonly;
        r.writeOnly = type && type->getQualifier().isWriteOnly();
        if (!classify(b.getBinding(), vulkan, true, false, false, readonly, &r.cls, &r.slot))
            fail("buffer block '" + r.name + "' binding " + std::to_string(b.getBinding()) +
                 " is outside the range of " + kClassNames[readonly ? kReadBuffer : kStorageBuffer] +
                 " (declare it with BL_READ_BUFFER for readonly, BL_STORAGE_BUFFER otherwise)");
        r.blockSize = b.size;
        out->bindings.push_back(r);
    }
    // Runtime arrays: the buffer variables reflection gives each top-level member's offset and stride.
    for (int i = 0; i < program.getNumBufferVariables(); ++i) {
        const TObjectReflection& v = program.getBufferVariable(i);
        const TType* t = v.getType();
        if (!t || !t->isUnsizedArray() || v.index < 0) continue;
        const TObjectReflection& block = program.getBufferBlock(v.index);
        for (auto& r : out->bindings)
            if (r.name == block.name && r.dimension == "Buffer") {
                r.blockSize = static_cast<unsigned>(v.offset);
                r.arrayStride = static_cast<unsigned>(v.topLevelArrayStride ? v.topLevelArrayStride : v.arrayStride);
            }
    }
    for (int i = 0; i < program.getNumUniformVariables(); ++i) {
        const TObjectReflection& u = program.getUniform(i);
        const TType* type = u.getType();
        if (!type || type->getBasicType() != EbtSampler) continue;
        const TSampler& s = type->getSampler();
        Binding r;
        r.name = u.name;
        bool image = s.isImage();
        if (!classify(u.getBinding(), vulkan, false, false, image, false, &r.cls, &r.slot))
            fail(std::string(image ? "image" : "sampler") + " '" + r.name + "' binding " +
                 std::to_string(u.getBinding()) + " is outside the range of " +
                 kClassNames[image ? kStorageImage : kTexture]);
        if (s.isPureSampler() || s.isBuffer() || s.isMultiSample())
            fail("'" + r.name + "': separate samplers, texel buffers and multisample textures are not supported");
        switch (s.dim) {
            case Esd2D: r.dimension = s.isArrayed() ? "Texture2DArray" : "Texture2D"; break;
            case Esd3D: r.dimension = "Texture3D"; break;
            case EsdCube: r.dimension = "TextureCube"; break;
            default: fail("'" + r.name + "': unsupported sampler dimension"); break;
        }
        if (s.dim == EsdCube && s.isArrayed()) fail("'" + r.name + "': cube arrays are not supported");
        r.scalar = scalarOf(s.type);
        r.shadow = s.isShadow();
        if (image) {
            const char* f = formatOf(type->getQualifier().getFormat());
            if (!f || std::string(f) == "Unknown")
                fail("image '" + r.name + "' needs a supported format qualifier (BL_IMAGE(slot, fmt))");
            else
                r.format = f;
            r.readOnly = type->getQualifier().isReadOnly();
            r.writeOnly = type->getQualifier().isWriteOnly();
        }
        out->bindings.push_back(r);
    }
    // Every resource the source declares, used or not (the linker objects keep all globals): a shared
    // include such as bricklight/trace.glsl declares the field's whole binding set, and which of it a
    // shader keeps is the compiler's business, so a record may bind the whole set (validation tells such
    // slots from ones the shader never declared).
    for (const Binding& b : out->bindings) out->declaredSlots[b.cls] |= 1u << b.slot;
    if (TIntermAggregate* root = program.getIntermediate(stage)->getTreeRoot()->getAsAggregate()) {
        TIntermAggregate* objects = root->getSequence().empty() ? nullptr : root->getSequence().back()->getAsAggregate();
        if (objects && objects->getOp() == EOpLinkerObjects)
            for (TIntermNode* node : objects->getSequence()) {
                TIntermSymbol* symbol = node->getAsSymbolNode();
                if (!symbol) continue;
                const TType& type = symbol->getType();
                const TQualifier& q = type.getQualifier();
                if (!q.hasBinding()) continue;
                const bool uniformBlock = type.getBasicType() == EbtBlock && q.storage == EvqUniform;
                const bool buffer = type.getBasicType() == EbtBlock && q.storage == EvqBuffer;
                const bool sampler = type.getBasicType() == EbtSampler;
                if (!uniformBlock && !buffer && !sampler) continue;
                int cls = 0, slot = 0;
                if (classify(int(q.layoutBinding), vulkan, buffer, uniformBlock, sampler && type.getSampler().isImage(),
                             q.isReadOnly(), &cls, &slot))
                    out->declaredSlots[cls] |= 1u << slot;
            }
    }
    if (stage == EShLangCompute)
        for (int d = 0; d < 3; ++d) out->localSize[d] = program.getLocalSize(d);
    if (stage == EShLangVertex)
        for (int i = 0; i < program.getNumPipeInputs(); ++i) {
            const TObjectReflection& in = program.getPipeInput(i);
            const TType* t = in.getType();
            if (!t || in.name.rfind("gl_", 0) == 0) continue;
            if (!t->getQualifier().hasLocation()) {
                fail("vertex input '" + in.name + "' needs layout(location = N)");
                continue;
            }
            out->inputs.push_back({in.name, static_cast<int>(t->getQualifier().layoutLocation),
                                   t->getVectorSize() ? t->getVectorSize() : 1, scalarOf(t->getBasicType())});
        }
    if (stage == EShLangFragment)
        for (int i = 0; i < program.getNumPipeOutputs(); ++i) {
            const TObjectReflection& o = program.getPipeOutput(i);
            const TType* t = o.getType();
            if (!t || o.name.rfind("gl_", 0) == 0) continue;
            int loc = t->getQualifier().hasLocation() ? static_cast<int>(t->getQualifier().layoutLocation) : 0;
            out->colorOutputMask |= 1u << loc;
        }
    // Two declarations of one class and slot would alias on one backend and not the other.
    std::set<std::pair<int, int>> seen;
    for (const auto& b : out->bindings)
        if (!seen.insert({b.cls, b.slot}).second)
            fail(std::string("two bindings share ") + kClassNames[b.cls] + " slot " + std::to_string(b.slot));
    return ok;
}

// glslang keeps pointers to the source pointers: they must outlive the TShader.
struct SourceText {
    const char* text;
    const char* path;
};

std::unique_ptr<glslang::TShader> makeShader(EShLanguage lang, const SourceText& src, bool vulkan) {
    auto shader = std::make_unique<glslang::TShader>(lang);
    shader->setStringsWithLengthsAndNames(&src.text, nullptr, &src.path, 1);
    shader->setEntryPoint("main");
    if (vulkan) {
        shader->setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientVulkan, 100);
        shader->setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
        shader->setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
    } else {
        shader->setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientOpenGL, 100);
        shader->setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
        shader->setEnvTarget(glslang::EShTargetNone, glslang::EShTargetSpv_1_0);
    }
    return shader;
}

std::string cString(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '\\') out += "\\\\";
        else if (c == '"') out += "\\\"";
        else if (c == '\n') out += "\\n\"\n\"";
        else if (c == '\r') continue;
        else out += c;
    }
    return out + "\"";
}

std::string identifier(const std::string& s) {
    std::string id;
    for (char c : s) id += (isalnum(static_cast<unsigned char>(c)) ? c : '_');
    return id;
}

// Keeps what the GL driver needs: drops #line directives naming files and the include extension.
std::string cleanPreprocessed(const std::string& text) {
    std::istringstream in(text);
    std::string line, out;
    while (std::getline(in, line)) {
        if (line.rfind("#line", 0) == 0) continue;
        if (line.find("GL_GOOGLE_include_directive") != std::string::npos) continue;
        if (line.find("GL_GOOGLE_cpp_style_line_directive") != std::string::npos) continue;
        bool blank = line.find_first_not_of(" \t") == std::string::npos;
        if (blank && !out.empty() && out.size() >= 2 && out[out.size() - 1] == '\n' && out[out.size() - 2] == '\n')
            continue;
        out += line + "\n";
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 5) {
        fprintf(stderr, "usage: bricklight-shaderc <name> <source> <out.cpp> <depfile> -I<dir>...\n");
        return 2;
    }
    std::string name = argv[1], source = argv[2], outPath = argv[3], depPath = argv[4];
    std::vector<std::string> includeDirs;
    for (int i = 5; i < argc; ++i)
        if (std::string(argv[i]).rfind("-I", 0) == 0) includeDirs.push_back(argv[i] + 2);

    const char* stageName = nullptr;
    EShLanguage lang = stageOf(source, &stageName);
    if (lang == EShLangCount) {
        fprintf(stderr, "%s: unknown stage (use .comp .vert .geom .frag)\n", source.c_str());
        return 1;
    }
    std::string text = readFile(source);
    if (text.empty()) {
        fprintf(stderr, "%s: cannot read\n", source.c_str());
        return 1;
    }
    glslang::InitializeProcess();
    const TBuiltInResource* limits = GetDefaultResources();
    const EShMessages msgs = static_cast<EShMessages>(EShMsgDefault);
    Includer includer(includeDirs);

    // Vulkan: SPIR-V and reflection.
    const SourceText original{text.c_str(), source.c_str()};
    auto vk = makeShader(lang, original, true);
    if (!vk->parse(limits, 100, false, static_cast<EShMessages>(msgs | EShMsgSpvRules | EShMsgVulkanRules),
                   includer)) {
        fprintf(stderr, "%s (Vulkan):\n%s\n", source.c_str(), vk->getInfoLog());
        return 1;
    }
    glslang::TProgram vkProgram;
    vkProgram.addShader(vk.get());
    if (!vkProgram.link(msgs)) {
        fprintf(stderr, "%s (Vulkan link):\n%s\n", source.c_str(), vkProgram.getInfoLog());
        return 1;
    }
    Reflection vkRefl;
    if (!reflect(vkProgram, lang, true, source, &vkRefl)) return 1;
    std::vector<unsigned> spirv;
    glslang::SpvOptions spvOptions;
    spvOptions.validate = true;
    glslang::GlslangToSpv(*vkProgram.getIntermediate(lang), spirv, &spvOptions);
    // SPIRV-Tools performance passes (inlining, SSA, dead code) on compute shaders: drivers take glslang's
    // literal SPIR-V less well than GLSL (NVIDIA ran the unoptimised brick pass ~3x slower on Vulkan than
    // on GL). Not on graphics stages: dead-code elimination would drop unused stage inputs and break the
    // interface matching between stages.
    if (lang == EShLangCompute) {
        spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_2);
        std::string optimizerMessages;
        optimizer.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) {
            optimizerMessages += std::string(m) + "\n";
        });
        optimizer.RegisterPerformancePasses();
        std::vector<uint32_t> optimized;
        if (!optimizer.Run(spirv.data(), spirv.size(), &optimized)) {
            fprintf(stderr, "%s: spirv-opt failed:\n%s\n", source.c_str(), optimizerMessages.c_str());
            return 1;
        }
        spirv.assign(optimized.begin(), optimized.end());
    }

    // OpenGL: preprocess without VULKAN, then compile that text as the GL driver will see it.
    auto glPre = makeShader(lang, original, false);
    std::string preprocessed;
    if (!glPre->preprocess(limits, 100, ENoProfile, false, false, msgs, &preprocessed, includer)) {
        fprintf(stderr, "%s (GL preprocess):\n%s\n", source.c_str(), glPre->getInfoLog());
        return 1;
    }
    std::string glsl = cleanPreprocessed(preprocessed);
    const SourceText forGl{glsl.c_str(), source.c_str()};
    auto gl = makeShader(lang, forGl, false);
    if (!gl->parse(limits, 100, false, msgs)) {
        fprintf(stderr, "%s (OpenGL):\n%s\n", source.c_str(), gl->getInfoLog());
        return 1;
    }
    glslang::TProgram glProgram;
    glProgram.addShader(gl.get());
    if (!glProgram.link(msgs)) {
        fprintf(stderr, "%s (OpenGL link):\n%s\n", source.c_str(), glProgram.getInfoLog());
        return 1;
    }
    Reflection glRefl;
    if (!reflect(glProgram, lang, false, source, &glRefl)) return 1;
    // Both variants must expose the same classes and slots under the same names.
    auto key = [](const Reflection& r) {
        std::set<std::string> k;
        for (const auto& b : r.bindings)
            k.insert(b.name + ":" + std::to_string(b.cls) + ":" + std::to_string(b.slot) + ":" + b.format);
        return k;
    };
    if (key(vkRefl) != key(glRefl)) {
        fprintf(stderr, "%s: the Vulkan and OpenGL variants disagree on bindings (use the BL_* macros)\n",
                source.c_str());
        return 1;
    }
    glslang::FinalizeProcess();

    std::string id = "blob_" + identifier(name);
    std::ostringstream o;
    o << "// Generated by bricklight-shaderc from " << name << ". Do not edit.\n";
    o << "#include \"bricklight/rhi.h\"\n\nnamespace {\nusing namespace bricklight::rhi;\n";
    o << "const uint32_t " << id << "_spirv[] = {";
    for (size_t i = 0; i < spirv.size(); ++i) o << (i % 8 ? " " : "\n    ") << spirv[i] << "u,";
    o << "\n};\n";
    o << "const ReflectedBinding " << id << "_bindings[] = {\n";
    for (const auto& b : vkRefl.bindings)
        o << "    {" << cString(b.name) << ", " << b.cls << ", " << b.slot << ", ResourceDimension::" << b.dimension
          << ", ResourceScalar::" << b.scalar << ", static_cast<uint8_t>(Format::" << b.format << "), "
          << (b.readOnly ? "true" : "false") << ", " << (b.writeOnly ? "true" : "false") << ", "
          << (b.shadow ? "true" : "false") << ", " << b.blockSize << "u, " << b.arrayStride << "u},\n";
    if (vkRefl.bindings.empty()) o << "    {\"\", 0, 0, ResourceDimension::None, ResourceScalar::None, 0, false, false, false, 0, 0},\n";
    o << "};\n";
    o << "const ReflectedVertexInput " << id << "_inputs[] = {\n";
    for (const auto& in : vkRefl.inputs)
        o << "    {" << cString(in.name) << ", " << in.location << ", " << in.components << ", ResourceScalar::"
          << in.scalar << "},\n";
    if (vkRefl.inputs.empty()) o << "    {\"\", 0, 0, ResourceScalar::None},\n";
    o << "};\n";
    o << "}  // namespace\n\n";
    // External linkage: the library's link_<target>() function names it (see BricklightShaders.cmake).
    o << "namespace bricklight::shaders {\nusing namespace bricklight::rhi;\n";
    o << "extern const ShaderBlob " << id << ";\n";
    o << "const ShaderBlob " << id << " = {\n    " << cString(name) << ", ShaderStage::" << stageName << ",\n"
      << cString(glsl) << ",\n    " << id << "_spirv, " << spirv.size() << ",\n    {{" << vkRefl.localSize[0]
      << ", " << vkRefl.localSize[1] << ", " << vkRefl.localSize[2] << "}, " << id << "_bindings, "
      << vkRefl.bindings.size() << ", " << id << "_inputs, " << vkRefl.inputs.size() << ", "
      << vkRefl.colorOutputMask << "u, {";
    for (int c = 0; c < 5; ++c) o << (c ? ", " : "") << vkRefl.declaredSlots[c] << "u";
    o << "}}};\n";
    o << "}  // namespace bricklight::shaders\n\n";
    o << "namespace {\nconst bricklight::rhi::detail::ShaderRegistration " << id << "_registration(&bricklight::shaders::" << id
      << ", 1);\n}  // namespace\n";

    std::ofstream out(outPath, std::ios::binary);
    out << o.str();
    if (!out) {
        fprintf(stderr, "%s: cannot write\n", outPath.c_str());
        return 1;
    }
    std::ofstream dep(depPath);
    dep << outPath << ": " << source;
    for (const auto& f : includer.files) dep << " \\\n  " << f;
    dep << "\n";
    return 0;
}
