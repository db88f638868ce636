#include "scene_wire.h"

#include <cmath>
#include <cstring>

namespace bricklight::scenes {

namespace {

constexpr uint32_t kMagic = 0x47534C42;  // "BLSG"
constexpr uint32_t kVersion = 2;  // 2: the alpha test
constexpr uint64_t kMaxStringBytes = 64ull << 20;  // names, paths, warnings and the error, together
constexpr uint64_t kMeshOverheadBytes = 128;       // a mesh's fixed fields and counts, with room to spare
constexpr uint64_t kMinMeshBytes = 93;             // the least a mesh takes (empty name and arrays)
constexpr uint64_t kPointLightBytes = 11 * 4;

class Writer {
public:
    std::vector<uint8_t> bytes;
    template <typename T>
    void raw(const T& v) {
        const auto* p = reinterpret_cast<const uint8_t*>(&v);
        bytes.insert(bytes.end(), p, p + sizeof v);
    }
    void u8(uint8_t v) { raw(v); }
    void u32(uint32_t v) { raw(v); }
    void u64(uint64_t v) { raw(v); }
    void f32(float v) { raw(v); }
    void vec3(const glm::vec3& v) {
        raw(v.x);
        raw(v.y);
        raw(v.z);
    }
    void string(const std::string& s) {
        u32(uint32_t(s.size()));
        bytes.insert(bytes.end(), s.begin(), s.end());
    }
    template <typename T>
    void array(const std::vector<T>& v) {
        u64(v.size());
        const auto* p = reinterpret_cast<const uint8_t*>(v.data());
        bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
    }
};

class Reader {
public:
    Reader(const uint8_t* p, size_t n) : p_(p), left_(n) {}
    bool ok() const { return problem_.empty(); }
    const std::string& problem() const { return problem_; }
    size_t left() const { return left_; }
    void fail(const std::string& why) {
        if (problem_.empty()) problem_ = why;
        left_ = 0;
    }
    template <typename T>
    T raw(const char* what) {
        T v{};
        if (left_ < sizeof v) {
            fail(std::string("it ends inside ") + what);
            return v;
        }
        std::memcpy(&v, p_, sizeof v);
        p_ += sizeof v;
        left_ -= sizeof v;
        return v;
    }
    uint8_t u8(const char* what) { return raw<uint8_t>(what); }
    uint32_t u32(const char* what) { return raw<uint32_t>(what); }
    uint64_t u64(const char* what) { return raw<uint64_t>(what); }
    float f32(const char* what) { return raw<float>(what); }
    glm::vec3 vec3(const char* what) {
        const float x = f32(what), y = f32(what), z = f32(what);
        return {x, y, z};
    }
    std::string string(const char* what) {
        const uint32_t n = u32(what);
        if (n > left_ || stringBytes_ + n > kMaxStringBytes) {
            fail(std::string(what) + " is longer than the reply or the " + std::to_string(kMaxStringBytes) + "-byte budget for text");
            return {};
        }
        stringBytes_ += n;
        std::string s(reinterpret_cast<const char*>(p_), n);
        p_ += n;
        left_ -= n;
        return s;
    }
    // A count of `elementBytes`-byte elements that must fit in what is left: checked before allocating.
    uint64_t count(const char* what, uint64_t elementBytes) {
        const uint64_t n = u64(what);
        if (elementBytes && n > left_ / elementBytes) fail(std::string(what) + " claims more elements than the reply holds");
        return ok() ? n : 0;
    }
    template <typename T>
    std::vector<T> array(const char* what) {
        const uint64_t n = count(what, sizeof(T));
        std::vector<T> v(static_cast<size_t>(n));
        if (n) std::memcpy(v.data(), p_, size_t(n) * sizeof(T));
        p_ += n * sizeof(T);
        left_ -= size_t(n * sizeof(T));
        return v;
    }

private:
    const uint8_t* p_;
    size_t left_;
    uint64_t stringBytes_ = 0;
    std::string problem_;
};

void encodeMesh(Writer& w, const TriangleMesh& m, int64_t embedded) {
    w.string(m.name);
    w.array(m.positions);
    w.array(m.indices);
    w.array(m.normals);
    w.array(m.uvs);
    w.string(m.baseColorTexture);
    w.raw(embedded);
    w.vec3(m.albedo);
    w.vec3(m.emission);
    w.f32(m.roughness);
    w.f32(m.metalness);
    w.u8(m.specular ? 1 : 0);
    w.f32(m.alphaCutoff);
    w.f32(m.baseAlpha);
    w.string(m.alphaTexture);
}

bool decodeMesh(Reader& r, const std::vector<std::shared_ptr<std::vector<uint8_t>>>& textures, TriangleMesh* m) {
    m->name = r.string("a mesh name");
    m->positions = r.array<float>("positions");
    m->indices = r.array<uint32_t>("indices");
    m->normals = r.array<float>("normals");
    m->uvs = r.array<float>("texture coordinates");
    m->baseColorTexture = r.string("a texture name");
    const int64_t embedded = r.raw<int64_t>("a mesh");
    m->albedo = r.vec3("a mesh");
    m->emission = r.vec3("a mesh");
    m->roughness = r.f32("a mesh");
    m->metalness = r.f32("a mesh");
    m->specular = r.u8("a mesh") != 0;
    m->alphaCutoff = r.f32("a mesh");
    m->baseAlpha = r.f32("a mesh");
    m->alphaTexture = r.string("a texture name");
    if (!r.ok()) return false;
    if (!(m->alphaCutoff >= 0.0f && m->alphaCutoff <= 1.0f) || !(m->baseAlpha >= 0.0f && m->baseAlpha <= 1.0f)) {  // NaN fails too
        r.fail("mesh '" + m->name + "' has an alpha cut-off or base alpha outside [0, 1]");
        return false;
    }
    const size_t vertices = m->positions.size() / 3;
    if (m->positions.size() % 3 || m->indices.size() % 3 || (!m->normals.empty() && m->normals.size() != m->positions.size()) ||
        (!m->uvs.empty() && m->uvs.size() != 2 * vertices)) {
        r.fail("mesh '" + m->name + "' has arrays of inconsistent lengths");
        return false;
    }
    for (uint32_t index : m->indices)
        if (index >= vertices) {
            r.fail("mesh '" + m->name + "' has an index past its vertices");
            return false;
        }
    if (embedded < -1 || embedded >= int64_t(textures.size())) {
        r.fail("mesh '" + m->name + "' names an embedded texture that is not there");
        return false;
    }
    if (embedded >= 0) m->embeddedTexture = textures[size_t(embedded)];
    return true;
}

}  // namespace

uint64_t maxImportResultBytes(const LoadLimits& limits) {
    // Positions, normals and texture coordinates per vertex; an index each; the embedded textures (at
    // most one file's worth); text; a mesh's fixed part for every triangle at most; the rest.
    const uint64_t meshes = limits.maxIndices / 3 + 16;
    return (1ull << 20) + limits.maxVertices * 32 + limits.maxIndices * 4 + limits.maxFileBytes + kMaxStringBytes +
           meshes * (kMeshOverheadBytes + 16 * 4 + 4);
}

std::vector<uint8_t> encodeImportResult(const SceneGeometry& s, const std::string& error) {
    Writer w;
    w.u32(kMagic);
    w.u32(kVersion);
    if (s.meshes.empty()) {
        w.u8(1);
        w.string(error.empty() ? "the importer gave no scene" : error);
        return std::move(w.bytes);
    }
    w.u8(0);
    w.string(s.name);
    // Embedded textures once each, however many meshes share them.
    std::vector<const std::vector<uint8_t>*> textures;
    std::vector<int64_t> textureOf;
    for (const TriangleMesh& m : s.meshes) {
        int64_t index = -1;
        if (m.embeddedTexture) {
            for (size_t i = 0; i < textures.size() && index < 0; ++i)
                if (textures[i] == m.embeddedTexture.get()) index = int64_t(i);
            if (index < 0) {
                index = int64_t(textures.size());
                textures.push_back(m.embeddedTexture.get());
            }
        }
        textureOf.push_back(index);
    }
    w.u32(uint32_t(textures.size()));
    for (const auto* t : textures) w.array(*t);
    w.u32(uint32_t(s.meshes.size()));
    for (size_t i = 0; i < s.meshes.size(); ++i) encodeMesh(w, s.meshes[i], textureOf[i]);
    w.u32(uint32_t(s.instances.size()));
    for (const MeshInstance& inst : s.instances) {
        w.u32(inst.mesh);
        for (int c = 0; c < 4; ++c)
            for (int k = 0; k < 4; ++k) w.f32(inst.transform[c][k]);
    }
    w.vec3(s.boundsMin);
    w.vec3(s.boundsMax);
    w.vec3(s.environment.skyRadiance);
    w.vec3(s.environment.sunDirection);
    w.vec3(s.environment.sunIrradiance);
    w.u32(uint32_t(s.pointLights.size()));
    for (const PointLight& l : s.pointLights) {
        w.vec3(l.position);
        w.vec3(l.intensity);
        w.vec3(l.direction);
        w.f32(l.innerConeRadians);
        w.f32(l.outerConeRadians);
    }
    w.vec3(s.camera.eye);
    w.vec3(s.camera.at);
    w.vec3(s.camera.up);
    w.f32(s.camera.verticalFovDegrees);
    w.u32(uint32_t(s.warnings.size()));
    for (const std::string& warning : s.warnings) w.string(warning);
    return std::move(w.bytes);
}

bool decodeImportResult(const uint8_t* bytes, size_t size, const LoadLimits& limits, SceneGeometry* scene, std::string* importError,
                        std::string* error) {
    Reader r(bytes, size);
    auto malformed = [&](const std::string& why) {
        if (error) *error = "the model importer's reply is malformed: " + why;
        *scene = SceneGeometry{};
        return false;
    };
    if (r.u32("the header") != kMagic || r.u32("the header") != kVersion) return malformed("no header");
    const uint8_t kind = r.u8("the header");
    if (kind == 1) {
        const std::string message = r.string("the error");
        if (!r.ok() || r.left()) return malformed(r.ok() ? "bytes after the error" : r.problem());
        *scene = SceneGeometry{};
        if (importError) *importError = message;
        return true;
    }
    if (kind != 0) return malformed("an unknown kind of reply");
    SceneGeometry s;
    s.name = r.string("the name");
    std::vector<std::shared_ptr<std::vector<uint8_t>>> textures;
    const uint32_t textureCount = r.u32("the textures");
    uint64_t textureBytes = 0;
    for (uint32_t i = 0; i < textureCount && r.ok(); ++i) {
        auto t = std::make_shared<std::vector<uint8_t>>(r.array<uint8_t>("a texture"));
        textureBytes += t->size();
        if (textureBytes > limits.maxFileBytes) return malformed("its embedded textures are larger than a model file may be");
        textures.push_back(std::move(t));
    }
    const uint32_t meshCount = r.u32("the meshes");
    if (uint64_t(meshCount) * kMinMeshBytes > r.left()) return malformed("more meshes than the reply holds");
    uint64_t vertices = 0, indices = 0;
    s.meshes.resize(meshCount);
    for (uint32_t i = 0; i < meshCount && r.ok(); ++i) {
        if (!decodeMesh(r, textures, &s.meshes[i])) break;
        vertices += s.meshes[i].positions.size() / 3;
        indices += s.meshes[i].indices.size();
        if (vertices > limits.maxVertices || indices > limits.maxIndices) return malformed("more vertices or indices than the limits allow");
    }
    const uint32_t instanceCount = r.u32("the instances");
    if (uint64_t(instanceCount) * 68 > r.left()) return malformed("more instances than the reply holds");
    s.instances.resize(instanceCount);
    for (MeshInstance& inst : s.instances) {
        inst.mesh = r.u32("an instance");
        if (inst.mesh >= meshCount) return malformed("an instance names a mesh that is not there");
        for (int c = 0; c < 4; ++c)
            for (int k = 0; k < 4; ++k) inst.transform[c][k] = r.f32("an instance");
    }
    s.boundsMin = r.vec3("the bounds");
    s.boundsMax = r.vec3("the bounds");
    s.environment.skyRadiance = r.vec3("the environment");
    s.environment.sunDirection = r.vec3("the environment");
    s.environment.sunIrradiance = r.vec3("the environment");
    const uint32_t lightCount = r.u32("the lights");
    if (uint64_t(lightCount) * kPointLightBytes > r.left()) return malformed("more lights than the reply holds");
    s.pointLights.resize(lightCount);
    for (PointLight& l : s.pointLights) {
        l.position = r.vec3("a light");
        l.intensity = r.vec3("a light");
        l.direction = r.vec3("a light");
        l.innerConeRadians = r.f32("a light");
        l.outerConeRadians = r.f32("a light");
    }
    s.camera.eye = r.vec3("the camera");
    s.camera.at = r.vec3("the camera");
    s.camera.up = r.vec3("the camera");
    s.camera.verticalFovDegrees = r.f32("the camera");
    const uint32_t warningCount = r.u32("the warnings");
    if (uint64_t(warningCount) * 4 > r.left()) return malformed("more warnings than the reply holds");
    for (uint32_t i = 0; i < warningCount && r.ok(); ++i) s.warnings.push_back(r.string("a warning"));
    if (!r.ok()) return malformed(r.problem());
    if (r.left()) return malformed(std::to_string(r.left()) + " bytes after the scene");
    if (s.meshes.empty()) return malformed("a scene without meshes");
    *scene = std::move(s);
    return true;
}

}  // namespace bricklight::scenes
