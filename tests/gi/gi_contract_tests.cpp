// The integration contract of SdfScene and GiContext: mistakes an integrator makes are caught with a
// stable ErrorCode and a message that names the objects; repeated messages reach the callback once and
// are counted; a scene destroyed under its context is an error, not a crash; optional inputs are optional;
// the camera self-check warns about a camera that does not match the depth buffer (y-flip, [-1, 1] depth,
// transposed matrices) and stays silent for a correct one. docs/gi.md ("Integration contract").
#include <cmath>
#include <functional>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "bricklight/half.h"
#include "image_metrics.h"
#include "raster_renderer.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kSize = 48;

std::unique_ptr<render::RasterRenderer> renderer(TestDevice& td, const scenes::SceneGeometry& scene) {
    auto r = sdfGiRenderer(td, scene, kSize);
    r->render();
    td.device->endFrame();
    return r;
}

// A context of our own beside the renderer's, with its messages collected (the callback's calls, not the
// diagnostics' counts).
struct OwnContext {
    std::unique_ptr<gi::GiContext> context;
    std::shared_ptr<std::vector<std::string>> messages = std::make_shared<std::vector<std::string>>();
    rhi::TextureHandle diffuse, specular;
    rhi::IDevice* device = nullptr;
    ~OwnContext() {
        context.reset();
        for (rhi::TextureHandle t : {diffuse, specular})
            if (t) device->destroy(t);
    }
};

void makeContext(TestDevice& td, const sdf::SdfScene& scene, OwnContext& own, uint32_t flags = 0) {
    own.device = td.device;
    gi::ContextDesc cd;
    cd.displayWidth = cd.displayHeight = kSize;
    cd.flags = flags;
    cd.debugName = "contract gi";
    auto messages = own.messages;
    cd.errorCallback = [messages](rhi::Severity, const std::string& m) { messages->push_back(m); };
    Error error;
    own.context = gi::GiContext::create(*td.device, scene, cd, &error);
    INFO(error.message);
    REQUIRE(own.context);
    rhi::TextureDesc od;
    od.format = rhi::Format::RGBA16_FLOAT;
    od.width = od.height = kSize;
    od.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    od.debugName = "contract diffuse";
    own.diffuse = td.device->createTexture(od);
    od.debugName = "contract specular";
    own.specular = td.device->createTexture(od);
    REQUIRE(own.diffuse);
    REQUIRE(own.specular);
}

// The renderer's G-buffer into our context's outputs; the previous camera is this one (a still view).
gi::DispatchDesc inputsOf(const render::GBufferView& g, const OwnContext& own) {
    gi::DispatchDesc d = giInputsOf(g, own.diffuse, own.specular);
    d.camera.previousView = g.view;
    d.camera.previousProjection = g.projection;
    return d;
}

// The diagnostic of that code (a copy: diagnostics() returns a fresh list).
std::optional<Diagnostic> find(const std::vector<Diagnostic>& all, ErrorCode code) {
    for (const Diagnostic& d : all)
        if (d.code == code) return d;
    return std::nullopt;
}

// Dispatches `frames` frames of `d` (ending each device frame, so read-backs come home).
void run(TestDevice& td, OwnContext& own, const gi::DispatchDesc& d, uint32_t frames) {
    for (uint32_t f = 0; f < frames; ++f) {
        REQUIRE(own.context->dispatch(d));
        td.device->endFrame();
    }
}

// The camera mistakes of the issue, applied to the matrices GI is given (the depth buffer was drawn with
// the right ones, as an engine's own renderer draws it).
struct CameraMistake {
    const char* name;
    std::function<void(gi::DispatchDesc&, const render::GBufferView&)> apply;
};
const CameraMistake kMistakes[] = {
    {"projection without the y-flip",
     [](gi::DispatchDesc& d, const render::GBufferView&) {
         d.camera.projection[1][1] = -d.camera.projection[1][1];
         d.camera.previousProjection = d.camera.projection;
     }},
    {"projection to [-1, 1] depth (GL style)",
     [](gi::DispatchDesc& d, const render::GBufferView& g) {
         // The same frustum as the renderer's (its near and far from its [0, 1] matrix), mapped to [-1, 1].
         const float a = g.projection[2][2], b = g.projection[3][2];  // z' = a z + b, w = -z
         const float nearPlane = b / a, farPlane = b / (a + 1.0f);
         glm::mat4 gl = glm::perspectiveRH_NO(2.0f * std::atan(1.0f / std::fabs(g.projection[1][1])),
                                              g.projection[1][1] / -g.projection[0][0], nearPlane, farPlane);
         gl[1][1] = -gl[1][1];
         d.camera.projection = d.camera.previousProjection = gl;
     }},
    {"transposed matrices",
     [](gi::DispatchDesc& d, const render::GBufferView&) {
         d.camera.view = d.camera.previousView = glm::transpose(d.camera.view);
         d.camera.projection = d.camera.previousProjection = glm::transpose(d.camera.projection);
     }},
};

void cameraSelfCheck(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    // The atrium seen from inside: walls, floor and pillars at many depths, nothing symmetric enough for
    // a mirrored camera to land on surfaces again.
    auto r = renderer(td, scenes::atrium());
    const render::GBufferView g = r->gbuffer();
    {
        OwnContext own;
        makeContext(td, *r->sdfScene(), own);
        run(td, own, inputsOf(g, own), 20);
        for (const std::string& m : *own.messages) UNSCOPED_INFO("message: " << m);
        CHECK(own.messages->empty());
        CHECK(find(own.context->diagnostics(), ErrorCode::CameraMismatch).has_value() == false);
    }
    for (const CameraMistake& mistake : kMistakes) {
        INFO("mistake: " << mistake.name);
        OwnContext own;
        makeContext(td, *r->sdfScene(), own);
        gi::DispatchDesc d = inputsOf(g, own);
        mistake.apply(d, g);
        run(td, own, d, 20);
        const std::optional<Diagnostic> warning = find(own.context->diagnostics(), ErrorCode::CameraMismatch);
        REQUIRE(warning);
        INFO("warning: " << warning->message);
        CHECK(warning->severity == rhi::Severity::Warning);
        CHECK(warning->count == 1);  // once
        CHECK(warning->message.find("y-flip") != std::string::npos);
        CHECK(warning->message.find("[-1, 1]") != std::string::npos);
        CHECK(warning->message.find("transposed") != std::string::npos);
        REQUIRE(own.messages->size() == 1);
        CHECK(*own.messages == std::vector<std::string>{warning->message});
    }
    {  // The check can be turned off (for a G-buffer that holds geometry the scene does not).
        OwnContext own;
        makeContext(td, *r->sdfScene(), own, gi::ContextFlags::NoCameraCheck);
        gi::DispatchDesc d = inputsOf(g, own);
        kMistakes[0].apply(d, g);
        run(td, own, d, 20);
        CHECK(own.messages->empty());
    }
    REQUIRE_NO_MESSAGES(td);
}

void repeatedErrorsAreCounted(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto r = renderer(td, scenes::cornellBox());
    OwnContext own;
    makeContext(td, *r->sdfScene(), own);
    gi::DispatchDesc d = inputsOf(r->gbuffer(), own);
    d.gbuffer.normals = {};
    for (int i = 0; i < 5; ++i) CHECK_FALSE(own.context->dispatch(d));
    CHECK(own.context->lastError().code == ErrorCode::MissingInput);
    REQUIRE(own.messages->size() == 1);  // the callback heard it once
    const std::optional<Diagnostic> missing = find(own.context->diagnostics(), ErrorCode::MissingInput);
    REQUIRE(missing);
    CHECK(missing->count == 5);
    CHECK(missing->message == own.context->lastError().message);
    CHECK(missing->message.find("contract gi: dispatch: input 'normals' is missing") != std::string::npos);
    // A different mistake is a new message; the first keeps its count.
    d = inputsOf(r->gbuffer(), own);
    d.outputDiffuse = r->gbuffer().lit;
    CHECK_FALSE(own.context->dispatch(d));
    CHECK(own.context->lastError().code == ErrorCode::Aliasing);
    CHECK(own.messages->size() == 2);
    CHECK(own.context->lastError().message.find("texture 'gbuffer lit' is bound as output 'outputDiffuse' and as input 'previousLitOutput'") !=
          std::string::npos);
    CHECK(find(own.context->diagnostics(), ErrorCode::MissingInput)->count == 5);
    REQUIRE_NO_MESSAGES(td);
}

void inputChecksByKindAndChannels(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto r = renderer(td, scenes::cornellBox());
    const render::GBufferView g = r->gbuffer();
    OwnContext own;
    makeContext(td, *r->sdfScene(), own);
    rhi::TextureDesc wide;
    wide.format = rhi::Format::RGBA32_FLOAT;
    wide.width = wide.height = kSize;
    wide.debugName = "rgba32 depth";
    rhi::TextureHandle rgbaDepth = td.device->createTexture(wide);
    REQUIRE(rgbaDepth);
    struct Case {
        const char* expect;
        ErrorCode code;
        std::function<void(gi::DispatchDesc&)> spoil;
    };
    const Case cases[] = {
        {"input 'depth' (texture 'rgba32 depth') has format RGBA32_FLOAT; it must hold one channel of device depth", ErrorCode::WrongFormat,
         [&](gi::DispatchDesc& d) { d.gbuffer.depth = rgbaDepth; }},
        {"input 'normals' (texture 'gbuffer depth') has format", ErrorCode::WrongFormat, [&](gi::DispatchDesc& d) { d.gbuffer.normals = g.depth; }},
        {"input 'motionVectors' (texture 'gbuffer depth') has format", ErrorCode::WrongFormat,
         [&](gi::DispatchDesc& d) { d.gbuffer.motionVectors = g.depth; }},
        {"input 'roughness' is not a live texture", ErrorCode::InvalidHandle, [](gi::DispatchDesc& d) { d.gbuffer.roughness = {999999}; }},
        {"trace.tMax must be greater", ErrorCode::InvalidArgument, [](gi::DispatchDesc& d) { d.trace.tMax = 0.0f; }},
        {"lightCount 65 is above kMaxLights", ErrorCode::OverBudget, [&](gi::DispatchDesc& d) {
             static gi::Light light;
             d.diffuseAlbedo = g.albedo;
             d.lights = &light;
             d.lightCount = 65;
         }},
        {"dispatch: lights[0] is an area light with no area", ErrorCode::InvalidArgument, [&](gi::DispatchDesc& d) {
             static gi::Light line;
             line.type = gi::LightType::Rect;
             line.color = glm::vec3(1.0f);
             line.edge0 = glm::vec3(1.0f, 0.0f, 0.0f);
             line.edge1 = glm::vec3(2.0f, 0.0f, 0.0f);  // parallel: a line, not a rectangle
             d.diffuseAlbedo = g.albedo;
             d.lights = &line;
             d.lightCount = 1;
         }},
        {"emittersInLights needs previousLitIncludesEmission = false", ErrorCode::InvalidArgument, [&](gi::DispatchDesc& d) {
             d.diffuseAlbedo = g.albedo;
             d.emittersInLights = true;
             d.previousLitIncludesEmission = true;
         }},
        {"lightUnseenSurfaces is set without 'diffuseAlbedo'", ErrorCode::MissingInput,
         [&](gi::DispatchDesc& d) { d.lightUnseenSurfaces = true; }},
    };
    for (const Case& c : cases) {
        gi::DispatchDesc d = inputsOf(g, own);
        c.spoil(d);
        CHECK_FALSE(own.context->dispatch(d));
        INFO("message: " << own.context->lastError().message);
        CHECK(own.context->lastError().message.find(c.expect) != std::string::npos);
        CHECK(own.context->lastError().code == c.code);
    }
    td.device->destroy(rgbaDepth);
    REQUIRE_NO_MESSAGES(td);
}

void motionVectorsAreOptional(const std::string& backend) {
    // A still camera with no motion vectors converges to the same GI as with the renderer's (zero) ones:
    // GI derives a still world's motion from depth and the two cameras.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto r = renderer(td, scenes::cornellBox());
    const render::GBufferView g = r->gbuffer();
    OwnContext with, without;
    makeContext(td, *r->sdfScene(), with);
    makeContext(td, *r->sdfScene(), without);
    gi::DispatchDesc a = inputsOf(g, with), b = inputsOf(g, without);
    b.gbuffer.motionVectors = {};
    for (int f = 0; f < 24; ++f) {
        REQUIRE(with.context->dispatch(a));
        REQUIRE(without.context->dispatch(b));
        td.device->endFrame();
    }
    std::vector<uint16_t> ha(kSize * kSize * 4), hb(kSize * kSize * 4);
    td.device->readTexture(with.diffuse, {}, ha.data());
    td.device->readTexture(without.diffuse, {}, hb.data());
    render::Image ia, ib;
    ia.width = ib.width = ia.height = ib.height = kSize;
    for (size_t i = 0; i < ha.size(); ++i)
        if (i % 4 != 3) {
            ia.rgb.push_back(halfToFloat(ha[i]));
            ib.rgb.push_back(halfToFloat(hb[i]));
        }
    double meanA = 0.0;
    for (float v : ia.rgb) meanA += v;
    meanA /= double(ia.rgb.size());
    const double difference = render::compareImages(ib, ia).relMse;
    INFO("mean " << meanA << ", relMSE without motion vectors vs with: " << difference);
    CHECK(meanA > 0.005);
    CHECK(difference < 1e-4);
    CHECK(with.messages->empty());
    CHECK(without.messages->empty());
    REQUIRE_NO_MESSAGES(td);
}

void sceneLifetimeAndUpdates(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto r = renderer(td, scenes::cornellBox());
    const render::GBufferView g = r->gbuffer();
    sdf::SceneDesc sd;
    sd.cascadeCount = 2;
    sd.finestVoxelSize = 0.05f;
    sd.atlasBricksPerAxis = 16;
    sd.debugName = "short-lived";
    sd.errorCallback = [](rhi::Severity, const std::string&) {};
    auto scene = sdf::SdfScene::create(*td.device, sd);
    REQUIRE(scene);
    OwnContext own;
    makeContext(td, *scene, own);
    gi::DispatchDesc d = inputsOf(g, own);
    // Never update()d: GI runs (there is nothing wrong with the inputs) and warns once.
    run(td, own, d, 3);
    const std::optional<Diagnostic> notUpdated = find(own.context->diagnostics(), ErrorCode::SceneNotUpdated);
    REQUIRE(notUpdated);
    CHECK(notUpdated->count == 3);
    CHECK(notUpdated->message.find("scene 'short-lived' was never update()d") != std::string::npos);
    CHECK(own.messages->size() == 1);
    // The scene goes first: every call that needs it is refused, and destroying the context is safe.
    scene.reset();
    CHECK_FALSE(own.context->dispatch(d));
    CHECK(own.context->lastError().code == ErrorCode::DependencyDestroyed);
    CHECK(own.context->lastError().message.find("sdf::SdfScene this context follows was destroyed") != std::string::npos);
    gi::DebugViewDesc view;
    CHECK_FALSE(own.context->debugView(view));
    CHECK(own.context->lastError().code == ErrorCode::DependencyDestroyed);
    std::vector<float> sh;
    own.context->readCaches(nullptr, &sh);
    CHECK(sh.empty());
    own.context.reset();
    REQUIRE_NO_MESSAGES(td);
}

void sdfErrorCodes(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    sdf::SceneDesc sd;
    sd.finestVoxelSize = 0.1f;
    sd.atlasBricksPerAxis = 8;
    std::vector<std::string> heard;
    sd.errorCallback = [&heard](rhi::Severity, const std::string& m) { heard.push_back(m); };
    Error error;
    sdf::SceneDesc bad = sd;
    bad.cascadeCount = 99;
    CHECK_FALSE(sdf::SdfScene::create(*td.device, bad, &error));
    CHECK(error.code == ErrorCode::InvalidArgument);
    CHECK(error.message.find("cascadeCount 99") != std::string::npos);
    auto scene = sdf::SdfScene::create(*td.device, sd, &error);
    REQUIRE(scene);
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t indices[] = {0, 1, 2};
    sdf::MeshArrays empty;
    empty.name = "empty";
    CHECK_FALSE(scene->createMesh(empty));
    CHECK(scene->lastError().code == ErrorCode::InvalidGeometry);
    CHECK_FALSE(scene->removeInstance({12345}));
    CHECK(scene->lastError().code == ErrorCode::InvalidHandle);
    sdf::MeshArrays triangle{positions, 3, indices, 3, "triangle"};
    sdf::MeshHandle mesh = scene->createMesh(triangle);
    REQUIRE(mesh);
    REQUIRE(scene->addInstance({mesh}));
    CHECK_FALSE(scene->destroyMesh(mesh));
    CHECK(scene->lastError().code == ErrorCode::InUse);
    CHECK(scene->lastError().message.find("destroyMesh 'triangle': still used by 1") != std::string::npos);
    CHECK_FALSE(scene->destroyMesh(mesh));
    CHECK(heard.size() == 4);  // the repeated destroyMesh is counted, not heard again
    CHECK(find(scene->diagnostics(), ErrorCode::InUse)->count == 2);
    CHECK(std::string(errorCodeName(ErrorCode::DependencyDestroyed)) == "DependencyDestroyed");
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("GI's camera self-check warns once about a camera that does not match the depth", "[gi][contract]", cameraSelfCheck)
BACKEND_TEST("GI counts a repeated error and reports it once", "[gi][contract]", repeatedErrorsAreCounted)
BACKEND_TEST("GI checks inputs by kind and channel count, with error codes", "[gi][contract]", inputChecksByKindAndChannels)
BACKEND_TEST("GI without motion vectors treats the world as still", "[gi][contract]", motionVectorsAreOptional)
BACKEND_TEST("GI refuses to run on a destroyed or never-updated scene", "[gi][contract]", sceneLifetimeAndUpdates)
BACKEND_TEST("SDF errors carry codes and repeat once", "[sdf][contract]", sdfErrorCodes)
