// bricklight_integration: the engine loop an integrator writes, built against the installed package
// (find_package(bricklight)), not against our source tree. Per frame:
//
//   application G-buffer draw ──► SdfScene::update(camera) ──► GiContext::dispatch(G-buffer, last lit image)
//     ──► application composite (sun + field-traced shadows + GI) ──► lit image ──► next frame's GI input
//
// Then it reads the last frame back, prints figures and checks them; the exit code is 0 only if every
// check passes and no layer (the validation wrapper, the backend, the Vulkan validation layer, the SDF
// builder, GI) said anything at all.
//
//   bricklight_integration [--backend vulkan|gl] [--frames N] [--size N] [--out FILE.ppm|FILE.pfm]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "bricklight/gi.h"
#include "bricklight/sdf.h"
#include "bricklight/version.h"
#include "checks.h"
#include "engine_device.h"
#include "passes.h"
#include "scene.h"

using namespace bricklight;
using namespace integration;

namespace {

struct Options {
    std::string backend = "vulkan";
    uint32_t frames = 32;
    uint32_t size = 96;
    std::string out;
};

int usage(const std::string& message) {
    fprintf(stderr, "bricklight_integration: %s\n"
                    "usage: bricklight_integration [--backend vulkan|gl] [--frames 1..10000] [--size 16..1024] [--out FILE.ppm|FILE.pfm]\n",
            message.c_str());
    return 2;
}

// The library's conventions (docs/gi.md, "Input conventions"): depth [0, 1] and clip-space y flipped so
// that NDC y = -1 is image row 0, the top. GLM's RH_ZO gives the depth range; the flip is ours to make.
glm::mat4 projectionMatrix(const Camera& camera, float aspect) {
    glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(camera.verticalFovDegrees), aspect, camera.nearPlane, camera.farPlane);
    p[1][1] = -p[1][1];
    return p;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool hasValue = i + 1 < argc;
        if (a == "--backend" && hasValue) o.backend = argv[++i];
        else if (a == "--frames" && hasValue) o.frames = uint32_t(std::strtoul(argv[++i], nullptr, 10));
        else if (a == "--size" && hasValue) o.size = uint32_t(std::strtoul(argv[++i], nullptr, 10));
        else if (a == "--out" && hasValue) o.out = argv[++i];
        else return usage("unknown option '" + a + "'");
    }
    if (o.frames < 1 || o.frames > 10000) return usage("--frames must be in 1..10000");
    if (o.size < 16 || o.size > 1024) return usage("--size must be in 16..1024");
    const auto start = std::chrono::steady_clock::now();

    // 1. The engine's device (engine_device_*.cpp): its own native objects, Bricklight's backend on them,
    //    the validation wrapper on top.
    std::string error;
    std::unique_ptr<EngineDevice> engine;
    if (o.backend == "vulkan") {
#ifdef INTEGRATION_HAS_VULKAN
        engine = createVulkanEngineDevice(&error);
#else
        return usage("the installed package has no Vulkan backend");
#endif
    } else if (o.backend == "gl") {
#ifdef INTEGRATION_HAS_GL
        engine = createGlEngineDevice(&error);
#else
        return usage("the installed package has no OpenGL backend");
#endif
    } else {
        return usage("unknown backend '" + o.backend + "' (vulkan or gl)");
    }
    if (!engine) {
        fprintf(stderr, "bricklight_integration: no %s device: %s\n", o.backend.c_str(), error.c_str());
        return 1;
    }
    rhi::IDevice& device = engine->device();
    printf("bricklight %s, %s\n", BRICKLIGHT_VERSION_STRING, engine->description().c_str());

    // Every object reports to the same log: the SDF builder and GI have callbacks of their own (bad input,
    // the camera self-check), separate from the device's.
    MessageLog& log = engine->messages();
    auto logAs = [&log](const char* source) {
        return [&log, source](rhi::Severity s, const std::string& m) { log.add(source, s, m); };
    };

    // 2. The application's scene, in its own buffers for its raster pass...
    const Room room = buildRoom();
    RoomBuffers roomBuffers;
    std::unique_ptr<Passes> passes;
    if (!uploadRoom(device, room, &roomBuffers, &error) || !(passes = Passes::create(device, o.size, o.size, &error))) {
        fprintf(stderr, "bricklight_integration: %s\n", error.c_str());
        return 1;
    }

    // 3. ...and in Bricklight's distance field. The field's cascades follow the camera: the finest covers
    //    64 voxels of 0.1 (±3.2 around the camera), each next one twice that, so four reach well past the
    //    room. The atlas and per-update budgets are sized for this small room (the defaults suit big scenes).
    sdf::SceneDesc sd;
    sd.cascadeCount = 4;
    sd.finestVoxelSize = 0.1f;
    sd.atlasBricksPerAxis = 32;  // 32³ = 32 768 bricks; the room takes about 21 000
    sd.budgets.maxTrianglesPerUpdate = 4096;
    sd.budgets.maxReferencesPerUpdate = 1u << 20;
    sd.debugName = "integration field";
    sd.errorCallback = logAs("sdf");
    Error refused;  // what the library says when it refuses a call: a code and a message
    std::unique_ptr<sdf::SdfScene> field = sdf::SdfScene::create(device, sd, &refused);
    if (!field) {
        fprintf(stderr, "bricklight_integration: %s (%s)\n", refused.message.c_str(), errorCodeName(refused.code));
        return 1;
    }
    if (!addRoomToField(*field, room, &error)) {
        fprintf(stderr, "bricklight_integration: %s\n", error.c_str());
        return 1;
    }

    // 4. GI at the display size (small images: no need to trace at a lower internal resolution).
    gi::ContextDesc cd;
    cd.displayWidth = o.size;
    cd.displayHeight = o.size;
    cd.internalResolution = gi::InternalResolution::Native;
    cd.debugName = "integration gi";
    cd.errorCallback = logAs("gi");
    std::unique_ptr<gi::GiContext> gi = gi::GiContext::create(device, *field, cd, &refused);
    if (!gi) {
        fprintf(stderr, "bricklight_integration: %s (%s)\n", refused.message.c_str(), errorCodeName(refused.code));
        return 1;
    }

    // The camera does not move, so last frame's matrices are this frame's; an engine keeps the previous
    // ones for motion vectors and GI's reprojection.
    const glm::mat4 view = glm::lookAtRH(room.camera.eye, room.camera.target, glm::vec3(0, 1, 0));
    const glm::mat4 projection = projectionMatrix(room.camera, 1.0f);
    const glm::mat4 viewProjection = projection * view;
    glm::mat4 previousView = view, previousProjection = projection;
    // The sun for GI's relighting of what the camera does not see: the same light our composite applies.
    gi::Light sun;
    sun.type = gi::LightType::Directional;
    sun.direction = room.sun.direction;
    sun.color = room.sun.irradiance;
    // Shadow rays start 1.5 finest voxels off the surface: past the field's distance band (2/7 voxel) of
    // the surface they leave, in the finest cascade and the next.
    const float shadowRayOffset = 1.5f * sd.finestVoxelSize;
    const FrameImages& images = passes->images();

    const auto loopStart = std::chrono::steady_clock::now();
    bool recorded = true;
    for (uint32_t frame = 0; frame < o.frames; ++frame) {
        engine->beginFrame();
        recorded &= passes->drawGBuffer(roomBuffers, viewProjection, previousProjection * previousView);
        field->update(room.camera.eye);  // rebuilds what changed (here: everything, once), then nothing
        gi::DispatchDesc d;
        d.camera.view = view;
        d.camera.projection = projection;
        d.camera.previousView = previousView;
        d.camera.previousProjection = previousProjection;
        d.cameraPosition = room.camera.eye;
        d.gbuffer.depth = images.depth;
        d.gbuffer.normals = images.normal;  // stored as-is in a float target: no unpacking
        d.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
        d.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
        d.gbuffer.roughness = images.albedo;
        d.gbuffer.roughnessChannel = 3;
        d.gbuffer.motionVectors = images.motion;
        d.previousLitOutput = images.lit;  // last frame's composite (zero in the first frame)
        d.diffuseAlbedo = images.albedo;   // with the lights: off-screen relighting
        d.lights = &sun;
        d.lightCount = 1;
        d.resetHistory = frame == 0;
        d.outputDiffuse = images.giDiffuse;
        d.outputSpecular = images.giSpecular;
        recorded &= gi->dispatch(d);
        recorded &= passes->composite(*field, viewProjection, room.camera.eye, room.sun, shadowRayOffset);
        engine->endFrame();
        previousView = view;
        previousProjection = projection;
    }
    engine->finish();
    const double loopMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loopStart).count();

    const sdf::Stats stats = field->latestStats();
    printf("ran %u frames of %ux%u in %.0f ms (%.1f ms/frame, start-up %.0f ms); field: %u bricks used of %u, %u voxels deferred\n",
           o.frames, o.size, o.size, loopMs, loopMs / o.frames,
           std::chrono::duration<double, std::milli>(loopStart - start).count(), stats.bricksUsed, stats.bricksCapacity,
           stats.voxelsDeferredGpu);

    CheckInputs ci;
    ci.room = &room;
    ci.viewProjection = viewProjection;
    ci.width = ci.height = o.size;
    ci.shadowRayOffset = shadowRayOffset;
    bool ok = checkFrame(device, images, ci);
    // The builder's counters come back a few updates late, without stalling: after 32 frames they are in.
    const bool fieldComplete = stats.update > 0 && stats.bricksUsed > 0 && stats.voxelsDeferredGpu == 0;
    ok &= reportCheck(fieldComplete, "the field was built whole (bricks used, no voxel deferred)");
    if (!o.out.empty()) {
        const bool written = writeLitImage(device, images, o.size, o.size, o.out);
        printf("  wrote %s%s\n", o.out.c_str(), written ? "" : " FAILED");
        ok &= written;
    }

    // Tear-down in dependency order: GI follows the field, both use the device.
    gi.reset();
    field.reset();
    passes.reset();
    destroyRoom(device, roomBuffers);
    device.waitIdle();
    ok &= reportCheck(recorded, "every record accepted");
    const uint64_t messages = log.count();
    ok &= reportCheck(messages == 0, "no messages from any layer (" + std::to_string(messages) + ")");
    printf("%s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
