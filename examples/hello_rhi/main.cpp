// hello_rhi: the first program an integrator reads. It creates a device, runs one compute pass and one
// draw as complete records, reads the image back and writes it as a PNG.
//
//   hello_rhi [--backend vulkan|gl] [--out FILE.png] [--size N]
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "bricklight/rhi.h"
#include "bricklight/rhi_validation.h"
#ifdef BRICKLIGHT_HAS_GL
#include "bricklight/rhi_gl.h"
#endif
#ifdef BRICKLIGHT_HAS_VULKAN
#include "bricklight/rhi_vulkan.h"
#endif

using namespace bricklight;

namespace {
int usage(const char* message) {
    fprintf(stderr, "hello_rhi: %s\nusage: hello_rhi [--backend vulkan|gl] [--out FILE.png] [--size 16..4096]\n", message);
    return 2;
}
}  // namespace

int main(int argc, char** argv) {
    std::string backend = "vulkan", outPath = "hello_rhi.png";
    uint32_t size = 256;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc) backend = argv[++i];
        else if (a == "--out" && i + 1 < argc) outPath = argv[++i];
        else if (a == "--size" && i + 1 < argc) size = uint32_t(std::strtoul(argv[++i], nullptr, 10));
        else return usage(("unknown option '" + a + "'").c_str());
    }
    if (size < 16 || size > 4096) return usage("--size must be in 16..4096");
    if (outPath.size() < 4 || outPath.compare(outPath.size() - 4, 4, ".png") != 0) return usage("--out must name a .png file");
    auto start = std::chrono::steady_clock::now();

    // 1. A device. Any IDevice works from here on; the validation wrapper checks every call we make.
    auto onError = [](rhi::Severity s, const std::string& m) {
        fprintf(stderr, "%s: %s\n", s == rhi::Severity::Error ? "error" : "warning", m.c_str());
    };
    std::unique_ptr<rhi::IDevice> native;
    std::string error;
    if (backend == "vulkan") {
#ifdef BRICKLIGHT_HAS_VULKAN
        vulkan::DeviceOptions options;
        options.errorCallback = onError;
        native = vulkan::createDevice(options);
#else
        return usage("this build has no Vulkan backend");
#endif
    } else if (backend == "gl") {
#ifdef BRICKLIGHT_HAS_GL
        native = gl::createHeadlessDevice(gl::HeadlessApi::Auto, onError, &error);
#else
        return usage("this build has no OpenGL backend");
#endif
    } else {
        return usage(("unknown backend '" + backend + "' (vulkan or gl)").c_str());
    }
    if (!native) {
        fprintf(stderr, "hello_rhi: could not create a %s device%s%s\n", backend.c_str(), error.empty() ? "" : ": ", error.c_str());
        return 1;
    }
    std::unique_ptr<rhi::IDevice> device = rhi::createValidationDevice(*native);
    device->setErrorCallback(onError);
    printf("hello_rhi: %s on %s\n", device->capabilities().backendName.c_str(), device->capabilities().deviceName.c_str());

    // 2. Resources: a storage texture the compute pass writes and the draw samples, and a render target.
    rhi::TextureDesc patternDesc;
    patternDesc.format = rhi::Format::RGBA8_UNORM;
    patternDesc.width = patternDesc.height = size;
    patternDesc.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    patternDesc.debugName = "pattern";
    rhi::TextureHandle pattern = device->createTexture(patternDesc);
    rhi::TextureDesc targetDesc = patternDesc;
    targetDesc.usage = rhi::TextureUsage::RenderTarget;
    targetDesc.debugName = "image";
    rhi::TextureHandle image = device->createTexture(targetDesc);
    rhi::SamplerHandle linear = device->createSampler(rhi::SamplerDesc{});
    const float vertices[] = {0.0f, -0.8f, 1, 0.3f, 0.2f, 0.8f, 0.7f, 0.2f, 1, 0.3f, -0.8f, 0.7f, 0.2f, 0.5f, 1};
    rhi::BufferDesc vbDesc;
    vbDesc.size = sizeof(vertices);
    vbDesc.usage = rhi::BufferUsage::Vertex;
    vbDesc.debugName = "triangle";
    rhi::BufferHandle triangle = device->createBuffer(vbDesc, vertices);
    rhi::ShaderHandle patternCs = device->createShader({rhi::findShader("examples/hello_pattern.comp"), ""});
    rhi::ShaderHandle triangleVs = device->createShader({rhi::findShader("examples/hello_triangle.vert"), ""});
    rhi::ShaderHandle triangleFs = device->createShader({rhi::findShader("examples/hello_triangle.frag"), ""});
    if (!pattern || !image || !triangle || !patternCs || !triangleVs || !triangleFs) return 1;

    // 3. A compute pass: the record names the shader and every binding, with constants inline.
    struct { int32_t width, height; float time; } computeParams{int32_t(size), int32_t(size), 0.7f};
    rhi::DispatchState compute;
    compute.shader = patternCs;
    compute.label = "pattern";
    compute.bindings.constants.push(rhi::constants(0, computeParams));
    compute.bindings.storageImages.push({0, rhi::textureMip(pattern, 0), rhi::Access::Write});
    if (!device->dispatch(compute, (size + 7) / 8, (size + 7) / 8, 1)) return 1;

    // 4. A draw that samples what the compute pass wrote; the backend places the barrier between them.
    const float drawParams[4] = {1.0f / size, 1.0f / size, 0, 0};
    rhi::DrawCallState draw;
    draw.vertexShader = triangleVs;
    draw.fragmentShader = triangleFs;
    draw.vertexInputs.push({0, rhi::VertexFormat::Float2, 0, 0});
    draw.vertexInputs.push({1, rhi::VertexFormat::Float3, 0, 8});
    draw.vertexBuffers.push({triangle, 0, 20, false});
    draw.bindings.constants.push(rhi::constants(0, drawParams));
    draw.bindings.textures.push({0, rhi::wholeTexture(pattern), linear});
    rhi::ColorTarget target;
    target.view = rhi::textureMip(image, 0);
    target.load = rhi::LoadOp::Load;
    draw.colorTargets.push(target);
    draw.label = "triangle";
    // The background: copy the pattern into the target, then draw the triangle over it.
    if (!device->copyTexture(image, {}, pattern, {})) return 1;
    if (!device->draw(draw, {3})) return 1;

    // 5. Read back (blocking; for tools and tests) and write a PNG.
    std::vector<uint8_t> pixels(size_t(size) * size * 4);
    if (!device->readTexture(image, {}, pixels.data())) return 1;
    // stb reports no write errors itself: the callback keeps the first (a full disk), and fclose's.
    struct Sink {
        FILE* file;
        bool ok;
    } sink{std::fopen(outPath.c_str(), "wb"), true};
    if (!sink.file) {
        fprintf(stderr, "hello_rhi: cannot write '%s': %s\n", outPath.c_str(), strerror(errno));
        return 1;
    }
    auto write = [](void* context, void* data, int size) {
        auto* s = static_cast<Sink*>(context);
        s->ok = s->ok && std::fwrite(data, 1, size_t(size), s->file) == size_t(size);
    };
    errno = 0;
    const bool encoded = stbi_write_png_to_func(write, &sink, int(size), int(size), 4, pixels.data(), int(size) * 4) != 0;
    const bool closed = std::fclose(sink.file) == 0;
    if (!encoded || !sink.ok || !closed) {
        fprintf(stderr, "hello_rhi: cannot write '%s': %s\n", outPath.c_str(), errno ? strerror(errno) : "the image writer failed");
        std::remove(outPath.c_str());
        return 1;
    }
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    printf("hello_rhi: wrote %s (%ux%u) in %.0f ms\n", outPath.c_str(), size, size, ms);
    return 0;
}
