// Linking the installed static archives by hand, with no CMake: proves that the SDF builder's and GI's
// shaders are inside their archives (libbricklight_sdf.a, libbricklight_gi.a; nothing is looked up on disk, and
// no loose object files are needed). scripts/test_package.sh builds and runs it:
//
//   g++ -std=c++20 -DHAND_LINK_VULKAN -DHAND_LINK_GL hand_link.cpp \
//       $(PKG_CONFIG_PATH=<prefix>/lib/pkgconfig pkg-config --cflags --libs bricklight)
//   ./a.out [--backend vulkan|gl]
//
// (HAND_LINK_VULKAN / HAND_LINK_GL: the backends the package was built with.)
//
// It creates a device (validation wrapper on), an SdfScene holding one box, updates it, checks that
// bricks were built, creates a GiContext, and exits 0 only if all of that worked with no message at all.
#include <cstdio>
#include <string>

#include "bricklight/gi.h"
#include "bricklight/rhi_validation.h"
#include "bricklight/sdf.h"
#ifdef HAND_LINK_VULKAN
#include "bricklight/rhi_vulkan.h"
#endif
#ifdef HAND_LINK_GL
#include "bricklight/rhi_gl.h"
#endif

using namespace bricklight;

int main(int argc, char** argv) {
    const std::string backend = argc == 3 && std::string(argv[1]) == "--backend" ? argv[2] : "vulkan";
    unsigned messages = 0;
    auto onMessage = [&messages](rhi::Severity, const std::string& m) {
        ++messages;
        fprintf(stderr, "hand_link: message: %s\n", m.c_str());
    };
    std::string error;
    std::unique_ptr<rhi::IDevice> native;
#ifdef HAND_LINK_VULKAN
    if (backend == "vulkan") {
        vulkan::DeviceOptions options;
        options.enableValidation = true;  // the Khronos layer; its messages come to the callback
        options.errorCallback = onMessage;
        native = vulkan::createDevice(options);
    }
#endif
#ifdef HAND_LINK_GL
    if (backend == "gl") native = gl::createHeadlessDevice(gl::HeadlessApi::Auto, onMessage, &error);
#endif
    if (!native) {
        fprintf(stderr, "hand_link: no %s device %s\n", backend.c_str(), error.c_str());
        return 1;
    }
    std::unique_ptr<rhi::IDevice> device = rhi::createValidationDevice(*native);
    device->setErrorCallback(onMessage);

    sdf::SceneDesc sd;
    sd.cascadeCount = 2;
    sd.finestVoxelSize = 0.05f;
    sd.atlasBricksPerAxis = 24;  // 13 824 bricks; the box needs about 6 000 in its two cascades
    sd.budgets.maxTrianglesPerUpdate = 1024;
    sd.budgets.maxReferencesPerUpdate = 1u << 18;
    sd.errorCallback = onMessage;
    Error refused;
    std::unique_ptr<sdf::SdfScene> scene = sdf::SdfScene::create(*device, sd, &refused);
    if (!scene) {
        fprintf(stderr, "hand_link: SdfScene::create failed: %s\n", refused.message.c_str());
        return 1;
    }
    // A 1 x 1 x 1 box: 8 corners, 12 triangles.
    const float p[] = {-0.5f, -0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, -0.5f, -0.5f, 0.5f, -0.5f,
                       -0.5f, -0.5f, 0.5f,  0.5f, -0.5f, 0.5f,  0.5f, 0.5f, 0.5f,  -0.5f, 0.5f, 0.5f};
    const uint32_t idx[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                            3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
    sdf::MeshArrays box;
    box.positions = p;
    box.vertexCount = 8;
    box.indices = idx;
    box.indexCount = 36;
    box.name = "box";
    sdf::InstanceDesc instance;
    instance.mesh = scene->createMesh(box);
    if (!instance.mesh || !scene->addInstance(instance)) {
        fprintf(stderr, "hand_link: the box was refused: %s\n", scene->lastError().message.c_str());
        return 1;
    }
    scene->update(glm::vec3(0.0f));

    // The field on the CPU (blocking): the finest cascade must hold bricks, i.e. the builder's passes ran.
    const sdf::FieldSnapshot field = scene->readField();
    uint32_t bricks = 0;
    if (!field.cascades.empty())
        for (uint32_t state : field.cascades[0].brickMap) bricks += state < sdf::FieldSnapshot::kEmpty;

    gi::ContextDesc cd;
    cd.displayWidth = cd.displayHeight = 64;
    cd.errorCallback = onMessage;
    std::unique_ptr<gi::GiContext> gi = gi::GiContext::create(*device, *scene, cd, &refused);  // creates every GI shader
    const bool giCreated = gi != nullptr;
    if (!giCreated) fprintf(stderr, "hand_link: GiContext::create failed: %s\n", refused.message.c_str());
    gi.reset();
    scene.reset();
    device->waitIdle();
    const bool ok = giCreated && bricks > 0 && messages == 0;
    printf("hand_link: %s: %u bricks in cascade 0, GI context %s, %u messages: %s\n", device->capabilities().backendName.c_str(),
           bricks, giCreated ? "created" : "FAILED", messages, ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
