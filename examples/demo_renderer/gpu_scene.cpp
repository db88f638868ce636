#include "gpu_scene.h"

#include <cmath>
#include <algorithm>
#include <cstring>
#include <numbers>

#include "bvh.h"
#include "generated_texture.h"
#include "texture_loader.h"

namespace bricklight::render {

namespace {
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
float bitsOf(uint32_t v) {
    float f;
    std::memcpy(&f, &v, 4);
    return f;
}
constexpr uint32_t kMaxBvhDepth = 48;  // the traversal stack of scene_trace.glsl
}  // namespace

bool checkImageSize(uint32_t width, uint32_t height, std::string* error) {
    if (width && height && width <= 16384 && height <= 16384) return true;
    if (error) *error = "image size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range (1..16384)";
    return false;
}

bool checkStorageRange(const rhi::IDevice& device, uint64_t bytes, const std::string& what, std::string* error) {
    const uint64_t range = device.capabilities().limits.maxStorageBufferRange;
    if (!range || bytes <= range) return true;
    if (error)
        *error = what + " needs " + std::to_string(bytes) + " bytes, more than this device's maxStorageBufferRange (" +
                 std::to_string(range) + " bytes)";
    return false;
}

bool checkCamera(const scenes::Camera& camera, std::string* error) {
    const glm::vec3 forward = camera.at - camera.eye;
    if (finite(camera.eye) && finite(camera.at) && glm::length(forward) > 0.0f && glm::length(glm::cross(forward, camera.up)) > 0.0f &&
        camera.verticalFovDegrees > 0.0f && camera.verticalFovDegrees < 180.0f)
        return true;
    if (error) *error = "the camera needs eye != at, an up vector not along the view, and a field of view in (0, 180)";
    return false;
}

std::unique_ptr<GpuScene> GpuScene::create(rhi::IDevice& device, const scenes::SceneGeometry& scene, std::string* error,
                                           const std::vector<glm::vec3>* previous) {
    auto fail = [&](const std::string& m) {
        if (error) *error = m;
        return std::unique_ptr<GpuScene>();
    };
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec3> shadingNormals;  // zero: use the triangle's normal
    std::vector<uint32_t> materialOf;
    // Glass last: the fast path draws the opaque triangles (the G-buffer, the voxelization) as one range and the
    // glass ones as another (raster_renderer_glass.cpp).
    uint32_t opaqueTriangles = 0;
    for (const auto& inst : scene.instances)
        if (inst.mesh >= scene.meshes.size()) return fail("an instance names mesh " + std::to_string(inst.mesh) + ", which does not exist");
    std::vector<const scenes::MeshInstance*> ordered;
    for (int glass = 0; glass < 2; ++glass)
        for (const auto& inst : scene.instances)
            if ((scene.meshes[inst.mesh].transmission > 0.0f) == (glass == 1)) ordered.push_back(&inst);
    for (const scenes::MeshInstance* instance : ordered) {
        const auto& inst = *instance;
        const auto& m = scene.meshes[inst.mesh];
        if (m.transmission <= 0.0f) opaqueTriangles += uint32_t(m.indices.size() / 3);
        for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = m.indices[i + size_t(k)];
                if (3 * size_t(v) + 2 >= m.positions.size())
                    return fail("mesh '" + m.name + "': index " + std::to_string(v) + " is out of range");
                const glm::vec3 p = glm::vec3(inst.transform * glm::vec4(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2], 1.0f));
                if (!finite(p)) return fail("mesh '" + m.name + "': vertex " + std::to_string(v) + " is not finite");
                positions.push_back(p);
                glm::vec3 sn(0.0f);
                if (3 * size_t(v) + 2 < m.normals.size()) {
                    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(inst.transform)));
                    sn = normalMatrix * glm::vec3(m.normals[3 * v], m.normals[3 * v + 1], m.normals[3 * v + 2]);
                    sn = finite(sn) && glm::length(sn) > 0.0f ? glm::normalize(sn) : glm::vec3(0.0f);
                }
                shadingNormals.push_back(sn);
                const bool hasUv = 2 * size_t(v) + 1 < m.uvs.size();
                uvs.push_back(hasUv ? glm::vec2(m.uvs[2 * v], m.uvs[2 * v + 1]) : glm::vec2(0.0f));
            }
            materialOf.push_back(inst.mesh);
        }
    }
    if (positions.empty()) return fail("the scene has no triangles");
    for (const auto& m : scene.meshes)
        if (!std::isfinite(m.roughness) || !std::isfinite(m.metalness) || m.roughness < 0.0f || m.roughness > 1.0f ||
            m.metalness < 0.0f || m.metalness > 1.0f)
            return fail("mesh '" + m.name + "': roughness and metalness must be in [0, 1]");
    for (const auto& m : scene.meshes) {
        if (!(m.transmission >= 0.0f && m.transmission <= 1.0f))  // NaN fails too
            return fail("mesh '" + m.name + "': transmission must be in [0, 1] (0 opaque, 1 clear glass), got " + std::to_string(m.transmission));
        if (!(m.ior > 1.0f && m.ior <= 3.0f))
            return fail("mesh '" + m.name + "': the index of refraction (ior) must be finite and in (1, 3], got " + std::to_string(m.ior));
        if (!(m.alphaCutoff >= 0.0f && m.alphaCutoff <= 1.0f) || !(m.baseAlpha >= 0.0f && m.baseAlpha <= 1.0f))
            return fail("mesh '" + m.name + "': alphaCutoff (0 opaque) and baseAlpha must be in [0, 1], got " + std::to_string(m.alphaCutoff) +
                        " and " + std::to_string(m.baseAlpha));
    }
    for (const auto& m : scene.meshes)
        if (!finite(m.albedo) || !finite(m.emission) || glm::any(glm::lessThan(m.albedo, glm::vec3(0.0f))) ||
            glm::any(glm::lessThan(m.emission, glm::vec3(0.0f))) || glm::any(glm::greaterThan(m.albedo, glm::vec3(1.0f))))
            return fail("mesh '" + m.name + "': albedo must be in [0, 1] and emission >= 0");
    const scenes::Environment& env = scene.environment;
    if (!finite(env.skyRadiance) || !finite(env.sunIrradiance) || !finite(env.sunDirection) ||
        glm::any(glm::lessThan(env.skyRadiance, glm::vec3(0.0f))) || glm::any(glm::lessThan(env.sunIrradiance, glm::vec3(0.0f))))
        return fail("the environment's sky and sun must be finite and non-negative");
    if (!(env.sunAngle >= 0.0f && env.sunAngle < 0.5f)) return fail("the sun's angle " + std::to_string(env.sunAngle) + " is outside 0..0.5 radians");

    std::vector<glm::vec4> points;
    for (const scenes::PointLight& l : scene.pointLights) {
        if (!finite(l.position) || !finite(l.intensity) || !finite(l.direction) || glm::any(glm::lessThan(l.intensity, glm::vec3(0.0f))))
            return fail("a point light has a non-finite position, intensity or direction, or a negative intensity");
        const bool spot = l.outerConeRadians < std::numbers::pi_v<float>;
        const glm::vec3 axis = glm::length(l.direction) > 0.0f ? glm::normalize(l.direction) : glm::vec3(0, -1, 0);
        points.push_back(glm::vec4(l.position, spot ? std::cos(l.outerConeRadians) : -2.0f));
        points.push_back(glm::vec4(l.intensity, 0.0f));
        points.push_back(glm::vec4(axis, spot ? std::cos(std::min(l.innerConeRadians, l.outerConeRadians)) : 1.0f));
    }
    const uint32_t pointCount = uint32_t(points.size() / 3);
    if (points.empty()) points.resize(3, glm::vec4(0.0f));
    Bvh bvh = buildBvh(positions);
    if (bvh.depth > kMaxBvhDepth) return fail("the BVH is " + std::to_string(bvh.depth) + " levels deep (the traversal stack holds 48)");
    const uint32_t n = uint32_t(positions.size() / 3);
    std::vector<glm::vec4> tris(3 * size_t(n)), lights;
    std::vector<float> vertices;
    vertices.reserve(size_t(n) * 45);
    const bool hasPrevious = previous && previous->size() == positions.size();
    for (uint32_t t = 0; t < n; ++t) {
        const glm::vec3 a = positions[3 * t], b = positions[3 * t + 1], c = positions[3 * t + 2];
        const glm::vec3 cr = glm::cross(b - a, c - a);
        const glm::vec3 normal = glm::length(cr) > 0.0f ? glm::normalize(cr) : glm::vec3(0, 1, 0);
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = positions[3 * t + size_t(k)], q = hasPrevious ? (*previous)[3 * t + size_t(k)] : p;
            const glm::vec2 uv = uvs[3 * t + size_t(k)];
            const glm::vec3 sn = shadingNormals[3 * t + size_t(k)] == glm::vec3(0.0f) ? normal : shadingNormals[3 * t + size_t(k)];
            vertices.insert(vertices.end(), {p.x, p.y, p.z, sn.x, sn.y, sn.z, bitsOf(materialOf[t]), q.x, q.y, q.z, uv.x, uv.y,
                                             normal.x, normal.y, normal.z});
        }
    }
    float total = 0.0f;
    for (uint32_t slot = 0; slot < n; ++slot) {
        const uint32_t t = bvh.order[slot];
        const uint32_t material = materialOf[t];
        const glm::vec3 a = positions[3 * t], b = positions[3 * t + 1], c = positions[3 * t + 2];
        tris[3 * slot] = glm::vec4(a, bitsOf(material));
        tris[3 * slot + 1] = glm::vec4(b, scene.meshes[material].alphaTested() ? 1.0f : 0.0f);  // traceRay's any-hit flag
        tris[3 * slot + 2] = glm::vec4(c, 0.0f);
        const float area = 0.5f * glm::length(glm::cross(b - a, c - a));
        const glm::vec3 e = scene.meshes[material].emission;
        const float weight = area * (0.2126f * e.r + 0.7152f * e.g + 0.0722f * e.b);
        if (weight > 0.0f) {
            total += weight;
            lights.push_back(glm::vec4(bitsOf(slot), area, total, weight));
        }
    }
    // Base-colour textures: one layer for each pair of base colour texture (a file or generated texels) and
    // opacity map (a pair used by several meshes is loaded once); an opacity map replaces its layer's alpha.
    struct Layer {
        std::string colour, coverage;
        const std::vector<uint8_t>* encoded;  // the colour texture's, when embedded in the model file
        const scenes::GeneratedTexture* generated;  // in place of the colour file
        std::string mesh;  // the first mesh that uses it, for messages
    };
    std::vector<Layer> layers;
    std::vector<float> layerOf;
    for (const auto& m : scene.meshes) {
        if (m.generatedTexture && !m.baseColorTexture.empty())
            return fail("mesh '" + m.name + "': has both a base colour texture file ('" + m.baseColorTexture + "') and a generated texture ('" +
                        m.generatedTexture->name + "')");
        float layer = -1.0f;
        const std::string coverage = m.alphaTested() ? m.alphaTexture : std::string();
        const scenes::GeneratedTexture* generated = m.generatedTexture.get();
        if (!m.baseColorTexture.empty() || generated || !coverage.empty()) {
            auto it = std::find_if(layers.begin(), layers.end(), [&](const Layer& l) {
                return l.colour == m.baseColorTexture && l.generated == generated && l.coverage == coverage;
            });
            layer = float(it - layers.begin());
            if (it == layers.end()) layers.push_back({m.baseColorTexture, coverage, m.embeddedTexture.get(), generated, m.name});
        }
        layerOf.push_back(layer);
    }
    const size_t layerBytes = size_t(kTextureSize) * kTextureSize * 4;
    std::vector<uint8_t> texels;
    for (const Layer& l : layers) {
        std::string textureError;
        if (l.generated) {
            if (!generatedTextureLayer(*l.generated, kTextureSize, &texels, &textureError)) return fail("mesh '" + l.mesh + "': " + textureError);
        } else if (l.colour.empty()) {
            texels.resize(texels.size() + layerBytes, 255);  // white, opaque
        } else if (!loadTextureLayer(l.colour, kTextureSize, &texels, &textureError, l.encoded, scene.loadLimits)) {
            return fail("mesh '" + l.mesh + "': base colour texture " + textureError);
        }
        if (l.coverage.empty()) continue;
        std::vector<uint8_t> coverage;
        if (!loadTextureLayer(l.coverage, kTextureSize, &coverage, &textureError, nullptr, scene.loadLimits, true))
            return fail("mesh '" + l.mesh + "': opacity map " + textureError);
        uint8_t* layer = texels.data() + texels.size() - layerBytes;
        for (size_t i = 3; i < layerBytes; i += 4) layer[i] = coverage[i];
    }
    if (layers.empty()) texels.assign(layerBytes, 255);  // one white layer
    std::vector<glm::vec4> materials;
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        const auto& m = scene.meshes[i];
        materials.push_back(glm::vec4(m.albedo, m.roughness));
        materials.push_back(glm::vec4(m.emission, m.metalness));
        materials.push_back(glm::vec4(layerOf[i], m.specular ? 0.04f : 0.0f, m.transmission, m.ior));
        materials.push_back(glm::vec4(m.alphaCutoff, m.baseAlpha, 0.0f, 0.0f));
    }
    std::vector<glm::vec4> triangleUvs(2 * size_t(n)), triangleNormals(3 * size_t(n));
    for (uint32_t slot = 0; slot < n; ++slot) {
        const uint32_t t = bvh.order[slot];
        triangleUvs[2 * slot] = glm::vec4(uvs[3 * t], uvs[3 * t + 1]);
        triangleUvs[2 * slot + 1] = glm::vec4(uvs[3 * t + 2], 0.0f, 0.0f);
        for (int k = 0; k < 3; ++k) triangleNormals[3 * slot + size_t(k)] = glm::vec4(shadingNormals[3 * t + size_t(k)], 0.0f);
    }
    const uint32_t lightCount = uint32_t(lights.size());
    if (lights.empty()) lights.push_back(glm::vec4(0.0f));  // a buffer is never empty

    std::unique_ptr<GpuScene> s(new GpuScene(device));
    s->environment_ = env;
    s->environment_.sunDirection = glm::length(env.sunDirection) > 0.0f ? glm::normalize(env.sunDirection) : glm::vec3(0, 1, 0);
    s->triangles_ = n;
    s->opaqueTriangles_ = opaqueTriangles;
    for (const auto& m : scene.meshes) s->alphaTested_ |= m.alphaTested();
    s->positions_ = std::move(positions);
    s->lightCount_ = lightCount;
    s->lightWeight_ = total;
    s->epsilon_ = 1e-5f * std::max(1.0f, glm::length(bvh.nodes[0].max - bvh.nodes[0].min));
    // Every buffer the passes bind whole, against the device's range, before creating any.
    const std::string triangles = "the scene's " + std::to_string(n) + " triangles";
    for (const auto& [bytes, what] : {std::pair{tris.size() * 16, triangles + " (positions)"},
                                      std::pair{bvh.nodes.size() * sizeof(BvhNode), triangles + " (their BVH)"},
                                      std::pair{triangleNormals.size() * 16, triangles + " (shading normals)"},
                                      std::pair{triangleUvs.size() * 16, triangles + " (texture coordinates)"},
                                      std::pair{lights.size() * 16, std::string("the scene's emitters")}})
        if (!checkStorageRange(device, uint64_t(bytes), what, error)) return nullptr;
    auto buffer = [&](const char* name, const void* data, uint64_t bytes, uint32_t usage) {
        rhi::BufferDesc d;
        d.size = bytes;
        d.usage = usage;
        d.debugName = std::string("scene ") + name;
        return device.createBuffer(d, data);
    };
    using namespace rhi::BufferUsage;
    s->triangleBuffer_ = buffer("triangles", tris.data(), tris.size() * 16, ShaderRead);
    s->nodes_ = buffer("bvh", bvh.nodes.data(), bvh.nodes.size() * sizeof(BvhNode), ShaderRead);
    s->materials_ = buffer("materials", materials.data(), materials.size() * 16, ShaderRead);
    s->lights_ = buffer("emitters", lights.data(), lights.size() * 16, ShaderRead);
    s->pointLights_ = buffer("point lights", points.data(), points.size() * 16, ShaderRead);
    s->pointLightCount_ = pointCount;
    s->vertices_ = buffer("vertices", vertices.data(), vertices.size() * 4, Vertex);
    s->uvs_ = buffer("texture coordinates", triangleUvs.data(), triangleUvs.size() * 16, ShaderRead);
    s->normals_ = buffer("shading normals", triangleNormals.data(), triangleNormals.size() * 16, ShaderRead);
    const uint32_t noneCutShort[4] = {0, 0, 0, 0};
    s->loopBudget_ = buffer("loop budget", noneCutShort, sizeof(noneCutShort), ShaderWrite);
    rhi::TextureDesc td;
    td.dimension = rhi::TextureDimension::Texture2DArray;
    td.format = rhi::Format::RGBA8_SRGB;
    td.width = td.height = kTextureSize;
    td.depthOrLayers = uint32_t(std::max<size_t>(1, layers.size()));
    td.debugName = "base colour textures";
    s->textures_ = device.createTexture(td, texels.data());
    rhi::SamplerDesc sd;
    sd.mipFilter = rhi::Filter::Nearest;
    sd.addressU = sd.addressV = rhi::AddressMode::Repeat;
    sd.debugName = "base colour";
    s->sampler_ = device.createSampler(sd);
    if (!s->triangleBuffer_ || !s->nodes_ || !s->materials_ || !s->lights_ || !s->pointLights_ || !s->vertices_ || !s->uvs_ || !s->normals_ ||
        !s->loopBudget_ || !s->textures_ || !s->sampler_)
        return fail("the device could not create the scene's buffers (see its messages)");
    return s;
}

GpuScene::~GpuScene() {
    for (rhi::BufferHandle b : {triangleBuffer_, nodes_, materials_, lights_, pointLights_, vertices_, uvs_, normals_, loopBudget_})
        if (b) device_.destroy(b);
    if (textures_) device_.destroy(textures_);
    if (sampler_) device_.destroy(sampler_);
}

void GpuScene::bind(rhi::Bindings& b) const {
    b.readBuffers.push({5, uvs_, {}});
    b.readBuffers.push({6, normals_, {}});
    b.textures.push({4, rhi::wholeTexture(textures_), sampler_});
    b.readBuffers.push({0, triangleBuffer_, {}});
    b.readBuffers.push({1, nodes_, {}});
    b.readBuffers.push({2, materials_, {}});
    b.readBuffers.push({3, lights_, {}});
    b.readBuffers.push({4, pointLights_, {}});
    b.storageBuffers.push({4, loopBudget_, {}, rhi::Access::Atomic});
}

uint64_t GpuScene::invocationsCutShort() const {
    uint32_t count = 0;
    device_.readBuffer(loopBudget_, 0, sizeof(count), &count);
    return count;
}

void GpuScene::bindVertices(rhi::DrawCallState& d) const {
    d.vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
    d.vertexInputs.push({1, rhi::VertexFormat::Float3, 0, 12});
    d.vertexInputs.push({2, rhi::VertexFormat::UInt1, 0, 24});
    d.vertexInputs.push({3, rhi::VertexFormat::Float3, 0, 28});
    d.vertexInputs.push({4, rhi::VertexFormat::Float2, 0, 40});
    d.vertexInputs.push({5, rhi::VertexFormat::Float3, 0, 48});
    d.vertexBuffers.push({vertices_, 0, kVertexStride, false});
}

void GpuScene::bindAlphaPass(rhi::DrawCallState& state, rhi::DrawArgs* args) const {
    state.vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
    state.vertexInputs.push({2, rhi::VertexFormat::UInt1, 0, 24});
    state.vertexInputs.push({4, rhi::VertexFormat::Float2, 0, 40});
    state.vertexBuffers.push({vertices_, 0, kVertexStride, false});
    state.bindings.readBuffers.push({2, materials_, {}});
    state.bindings.textures.push({4, rhi::wholeTexture(textures_), sampler_});
    *args = rhi::DrawArgs{};
    args->vertexCount = 3 * triangles_;  // alpha_pass.vert drops the triangles of materials without a cut-off
}

SceneLightConstants GpuScene::lightConstants(uint32_t seed, uint32_t maxBounces) const {
    SceneLightConstants c{};
    c.sky = glm::vec4(environment_.skyRadiance, 0.0f);
    // w: the radius of the sun's disc at distance 1 (tan of half its angle); 0 a point sun.
    c.sunDirection = glm::vec4(environment_.sunDirection, std::tan(0.5f * environment_.sunAngle));
    c.sunIrradiance = glm::vec4(environment_.sunIrradiance, 0.0f);
    c.counts[0] = lightCount_;
    c.counts[1] = seed;
    c.counts[2] = maxBounces;
    c.counts[3] = pointLightCount_;
    c.lightWeight = glm::vec4(lightWeight_, epsilon_, 0.0f, 0.0f);
    return c;
}

}  // namespace bricklight::render
