// The SDF GI in the demo renderer (RasterOptions::gi; docs/gi.md): the context on the renderer's field, its dispatch on
// the G-buffer each frame, and what the tools read back.
#include "raster_renderer.h"

#include <glm/gtc/packing.hpp>

#include "bricklight/half.h"

namespace bricklight::render {

namespace {

// The emitting triangles of the scene as GI's area lights, a triangle pair that forms a parallelogram (a quad's two
// halves, a → b → c and a → c → d) as one Rect. False if they do not fit in `room` lights.
bool appendEmitters(const scenes::SceneGeometry& scene, size_t room, std::vector<gi::Light>& lights) {
    std::vector<gi::Light> emitters;
    for (const scenes::MeshInstance& instance : scene.instances) {
        const scenes::TriangleMesh& mesh = scene.meshes[instance.mesh];
        if (!(mesh.emission.x > 0.0f || mesh.emission.y > 0.0f || mesh.emission.z > 0.0f)) continue;
        auto corner = [&](uint32_t index) {
            const float* v = &mesh.positions[3 * size_t(mesh.indices[index])];
            return glm::vec3(instance.transform * glm::vec4(v[0], v[1], v[2], 1.0f));
        };
        const size_t triangles = mesh.indices.size() / 3;
        for (size_t t = 0; t < triangles; ++t) {
            const glm::vec3 a = corner(uint32_t(3 * t)), b = corner(uint32_t(3 * t + 1)), c = corner(uint32_t(3 * t + 2));
            const float area = glm::length(glm::cross(b - a, c - a));
            if (!(area > 0.0f)) continue;  // emits nothing
            gi::Light l;
            l.type = gi::LightType::Triangle;
            l.position = a;
            l.edge0 = b - a;
            l.edge1 = c - a;
            l.color = mesh.emission;
            if (t + 1 < triangles) {
                const glm::vec3 a2 = corner(uint32_t(3 * t + 3)), c2 = corner(uint32_t(3 * t + 4)), d = corner(uint32_t(3 * t + 5));
                const float tolerance = 1e-5f * std::sqrt(area);
                if (glm::length(a2 - a) <= tolerance && glm::length(c2 - c) <= tolerance && glm::length(a + c - b - d) <= tolerance) {
                    l.type = gi::LightType::Rect;
                    l.edge1 = d - a;
                    ++t;
                }
            }
            if (emitters.size() == room) return false;
            emitters.push_back(l);
        }
    }
    lights.insert(lights.end(), emitters.begin(), emitters.end());
    return true;
}

}  // namespace

// The scene's sun, point/spot lights and emitting surfaces, for GI's relighting of what the camera does not see.
// (The sky is not among them: it is GI's environment, which the renderer's direct lighting holds — dispatchGi.)
GiLights giLightsOf(const scenes::SceneGeometry& scene) {
    GiLights out;
    std::vector<gi::Light>& lights = out.lights;
    const scenes::Environment& env = scene.environment;
    if (env.sunIrradiance.x > 0.0f || env.sunIrradiance.y > 0.0f || env.sunIrradiance.z > 0.0f) {
        gi::Light sun;
        sun.type = gi::LightType::Directional;
        sun.direction = env.sunDirection;
        sun.color = env.sunIrradiance;
        lights.push_back(sun);
    }
    for (const scenes::PointLight& p : scene.pointLights) {
        if (lights.size() == gi::kMaxLights) break;
        gi::Light l;
        const bool spot = p.outerConeRadians <= 3.14159265f;
        l.type = spot ? gi::LightType::Spot : gi::LightType::Point;
        l.position = p.position;
        l.direction = p.direction;
        l.color = p.intensity;
        if (spot) {
            l.spotOuterAngle = p.outerConeRadians;
            l.spotInnerAngle = std::min(p.innerConeRadians, p.outerConeRadians);
        }
        lights.push_back(l);
    }
    // More emitting triangles than lights left: relight rays take the emission where they hit instead.
    out.emittersInLights = appendEmitters(scene, gi::kMaxLights - lights.size(), lights);
    const glm::vec3 sky = env.skyRadiance;
    out.sky = glm::max(sky, glm::vec3(0.0f));
    out.allDirectLight = out.emittersInLights && sky.x <= 0.0f && sky.y <= 0.0f && sky.z <= 0.0f;
    return out;
}

bool RasterRenderer::createGi(const scenes::SceneGeometry& scene, std::string* error) {
    if (!sdf_ && !createSdf(scene, error)) return false;
    Error why;
    gi::ContextDesc gd;
    gd.displayWidth = options_.width;
    gd.displayHeight = options_.height;
    gd.internalResolution = options_.giResolution;
    gd.radianceCacheBricks = options_.giCacheBricks;
    gd.injectTile = options_.giInjectTile;
    gd.probeTile = options_.giProbeTile;
    gd.flags |= options_.giFlags;
    gd.debugName = "render gi";
    gd.errorCallback = options_.errorCallback;
    if (alphaAwareFoliage()) gd.flags |= gi::ContextFlags::AlphaCache;
    // Cards left out of the field are in the G-buffer all the same: the camera self-check would count them.
    if (options_.foliage == FoliageMode::LeftOut && scene_->hasAlphaTested()) gd.flags |= gi::ContextFlags::NoCameraCheck;
    gi_ = gi::GiContext::create(device_, *sdf_, gd, &why);
    if (!gi_) {
        if (error) *error = "raster renderer: " + why.message;
        return false;
    }
    rhi::TextureDesc sky;
    sky.format = rhi::Format::RGBA16_FLOAT;  // linear filtering of 32-bit floats is optional in Vulkan
    sky.width = sky.height = 1;
    sky.usage = rhi::TextureUsage::Sampled;
    sky.debugName = "gi sky";
    giSky_ = device_.createTexture(sky);
    if (!giSky_) {
        if (error) *error = "raster renderer: the device could not create GI's sky texture (see its messages)";
        return false;
    }
    return !alphaAwareFoliage() || createAlphaPass(error);
}

void RasterRenderer::dispatchGi(bool cut) {
    if (!gi_) return;
    gi::DispatchDesc g;
    g.camera = frameCamera();
    g.gbuffer = frameGBuffer();
    g.cameraPosition = camera_.eye;
    g.previousLitOutput = lit_;
    if (options_.giRelight) {
        g.diffuseAlbedo = albedo_;  // base colour: metals' (small) diffuse part is overestimated off screen
        // The lit image fed back leaves emission out (direct lighting samples the emitters): re-lit
        // texels leave it out too, and their rays add it where they hit an emitter.
        g.emission = emission_;
        g.previousLitIncludesEmission = false;
        g.lights = giLights_.lights.data();
        g.lightCount = uint32_t(giLights_.lights.size());
        g.emittersInLights = giLights_.emittersInLights;
        g.lightUnseenSurfaces = giLights_.allDirectLight || options_.giUnseenPath;
        g.relightBounces = options_.giFeedback;  // --single-bounce: one bounce everywhere, not only on screen
    }
    // The sky lights the renderer's pixels in its direct lighting (BRDF-sampled, diffuse and glossy): GI takes it only
    // where it lights surfaces in the screen's place (re-lit texels off screen); rays for pixels take none of it.
    if (giLights_.sky != giSkyUploaded_) {
        const uint64_t texel = glm::packHalf4x16(glm::vec4(glm::min(giLights_.sky, glm::vec3(65504.0f)), 1.0f));
        if (device_.writeTexture(giSky_, {}, &texel)) giSkyUploaded_ = giLights_.sky;
    }
    if (giSkyUploaded_ == giLights_.sky && (giLights_.sky.x > 0.0f || giLights_.sky.y > 0.0f || giLights_.sky.z > 0.0f)) {
        g.environmentKind = gi::EnvironmentKind::Equirectangular;
        g.environmentMap = giSky_;
        g.environmentInDirectLight = true;
    }
    g.outputDiffuse = giDiffuse_;
    g.outputSpecular = giSpecular_;
    g.trace = options_.giTrace;
    g.roughnessThreshold = options_.giRoughnessThreshold;
    g.resetHistory = cut;
    g.unseenLight = options_.giUnseenFromVct ? clipmap_.get() : nullptr;
    gi_->dispatch(g);
}

Image RasterRenderer::readGi(rhi::TextureHandle t) {
    Image img;
    img.width = options_.width;
    img.height = options_.height;
    const size_t pixels = size_t(img.width) * img.height;
    img.rgb.assign(pixels * 3, 0.0f);
    std::vector<uint16_t> h(pixels * 4);
    device_.readTexture(t, {}, h.data());
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = halfToFloat(h[4 * i + size_t(c)]);
    return img;
}

Image RasterRenderer::readSpecularGi() { return readGi(giSpecular_); }

Image RasterRenderer::giDebugView(gi::DebugMode mode, float exposure) {
    Image img;
    if (!gi_) return img;
    rhi::TextureDesc d;
    d.format = rhi::Format::RGBA8_UNORM;
    d.width = options_.width;
    d.height = options_.height;
    d.usage = rhi::TextureUsage::Storage;
    d.debugName = "gi debug view";
    rhi::TextureHandle t = device_.createTexture(d);
    if (!t) return img;
    gi::DebugViewDesc desc;
    desc.mode = mode;
    desc.output = t;
    desc.exposure = exposure;
    if (gi_->debugView(desc)) {
        std::vector<uint8_t> bytes(size_t(d.width) * d.height * 4);
        device_.readTexture(t, {}, bytes.data());
        img.width = d.width;
        img.height = d.height;
        img.rgb.resize(size_t(d.width) * d.height * 3);
        for (size_t i = 0; i < img.rgb.size() / 3; ++i)
            for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = float(bytes[4 * i + size_t(c)]) / 255.0f;
    }
    device_.destroy(t);
    return img;
}

}  // namespace bricklight::render
