// The out-of-process importer's reply format: a scene survives the round trip, and no malformed reply
// (cut short, corrupted, lying counts, references past the end) crashes the decoder or makes it allocate
// more than the reply holds.
#include "test_support.h"

#include <cmath>
#include <cstring>

#include "scene_geometry.h"
#include "scene_wire.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

scenes::SceneGeometry sampleScene() {
    scenes::SceneGeometry s;
    s.name = "sample.glb";
    auto texture = std::make_shared<std::vector<uint8_t>>(std::vector<uint8_t>{1, 2, 3, 4, 5});
    for (int i = 0; i < 2; ++i) {
        scenes::TriangleMesh m;
        m.name = "mesh " + std::to_string(i);
        m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        m.indices = {0, 1, 2};
        m.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
        m.uvs = {0, 0, 1, 0, 0, 1};
        m.baseColorTexture = "sample.glb*0.png";
        m.embeddedTexture = texture;  // shared: sent once
        m.albedo = glm::vec3(0.5f, 0.25f, 0.125f);
        m.emission = glm::vec3(float(i));
        m.roughness = 0.3f;
        m.metalness = 0.7f;
        m.specular = i == 1;
        m.alphaCutoff = 0.25f * float(i);
        m.baseAlpha = 0.5f;
        m.alphaTexture = i == 1 ? "leaf.png" : "";
        s.meshes.push_back(m);
        s.instances.push_back({uint32_t(i), glm::mat4(float(i + 1))});
    }
    s.pointLights.push_back({glm::vec3(1, 2, 3), glm::vec3(4), glm::vec3(0, -1, 0), 0.5f, 0.7f});
    s.environment.skyRadiance = glm::vec3(0.1f);
    s.camera.eye = glm::vec3(0, 0, 9);
    s.warnings = {"a warning"};
    s.computeBounds();
    return s;
}

}  // namespace

TEST_CASE("loading: a scene survives the importer's reply format", "[loading]") {
    const scenes::SceneGeometry in = sampleScene();
    const std::vector<uint8_t> bytes = scenes::encodeImportResult(in, "");
    scenes::SceneGeometry out;
    std::string importError, error;
    REQUIRE(scenes::decodeImportResult(bytes.data(), bytes.size(), {}, &out, &importError, &error));
    INFO(error);
    REQUIRE(out.meshes.size() == 2);
    CHECK(out.name == in.name);
    for (size_t i = 0; i < 2; ++i) {
        const auto &a = in.meshes[i], &b = out.meshes[i];
        CHECK(a.name == b.name);
        CHECK(a.positions == b.positions);
        CHECK(a.indices == b.indices);
        CHECK(a.normals == b.normals);
        CHECK(a.uvs == b.uvs);
        CHECK(a.baseColorTexture == b.baseColorTexture);
        REQUIRE(b.embeddedTexture);
        CHECK(*a.embeddedTexture == *b.embeddedTexture);
        CHECK(a.albedo == b.albedo);
        CHECK(a.emission == b.emission);
        CHECK(a.roughness == b.roughness);
        CHECK(a.metalness == b.metalness);
        CHECK(a.specular == b.specular);
        CHECK(a.alphaCutoff == b.alphaCutoff);
        CHECK(a.baseAlpha == b.baseAlpha);
        CHECK(a.alphaTexture == b.alphaTexture);
        CHECK(in.instances[i].mesh == out.instances[i].mesh);
        CHECK(in.instances[i].transform == out.instances[i].transform);
    }
    CHECK(out.meshes[0].embeddedTexture == out.meshes[1].embeddedTexture);  // still one texture
    CHECK(out.pointLights.size() == 1);
    CHECK(out.pointLights[0].outerConeRadians == 0.7f);
    CHECK(out.environment.skyRadiance == in.environment.skyRadiance);
    CHECK(out.camera.eye == in.camera.eye);
    CHECK(out.boundsMax == in.boundsMax);
    CHECK(out.warnings == in.warnings);
    // An import error travels as such.
    const std::vector<uint8_t> failure = scenes::encodeImportResult({}, "'x.ply': broken");
    REQUIRE(scenes::decodeImportResult(failure.data(), failure.size(), {}, &out, &importError, &error));
    CHECK(out.meshes.empty());
    CHECK(importError == "'x.ply': broken");
}

TEST_CASE("loading: malformed importer replies are errors, never crashes", "[loading]") {
    const std::vector<uint8_t> bytes = scenes::encodeImportResult(sampleScene(), "");
    scenes::SceneGeometry out;
    std::string importError, error;
    // Every prefix is malformed.
    for (size_t n = 0; n < bytes.size(); ++n) {
        INFO("the first " << n << " bytes");
        CHECK(!scenes::decodeImportResult(bytes.data(), n, {}, &out, &importError, &error));
        CHECK(matches(error, "^the model importer's reply is malformed: "));
    }
    // Every byte set to 0xFF (lying counts, lengths, indices): decodes or is refused, never more; a bad
    // header (magic, version, kind: the first 9 bytes) is always refused.
    for (size_t i = 0; i < bytes.size(); ++i) {
        std::vector<uint8_t> bad = bytes;
        bad[i] = 0xFF;
        const bool decoded = scenes::decodeImportResult(bad.data(), bad.size(), {}, &out, &importError, &error);
        if (i < 9) CHECK(!decoded);
        for (const auto& m : out.meshes)
            for (uint32_t index : m.indices) CHECK(index < m.positions.size() / 3);
    }
    // An index past the vertices is refused (the renderer would read outside the mesh).
    scenes::SceneGeometry s = sampleScene();
    s.meshes[0].indices[2] = 3;
    const std::vector<uint8_t> pastEnd = scenes::encodeImportResult(s, "");
    CHECK(!scenes::decodeImportResult(pastEnd.data(), pastEnd.size(), {}, &out, &importError, &error));
    CHECK(matches(error, "index past its vertices"));
    // An alpha cut-off or base alpha that is not a number or outside [0, 1] (GpuScene would test against it).
    for (float bad : {std::nanf(""), -0.5f, 1.5f})
        for (int field = 0; field < 2; ++field) {
            INFO(bad << " as field " << field);
            s = sampleScene();
            (field ? s.meshes[1].baseAlpha : s.meshes[1].alphaCutoff) = bad;
            const std::vector<uint8_t> badAlpha = scenes::encodeImportResult(s, "");
            CHECK(!scenes::decodeImportResult(badAlpha.data(), badAlpha.size(), {}, &out, &importError, &error));
            CHECK(matches(error, "mesh 'mesh 1' has an alpha cut-off or base alpha outside \\[0, 1\\]"));
        }
    // More vertices than the limits allow.
    scenes::LoadLimits limits;
    limits.maxVertices = 5;
    CHECK(!scenes::decodeImportResult(bytes.data(), bytes.size(), limits, &out, &importError, &error));
    CHECK(matches(error, "more vertices or indices than the limits allow"));
    // Bytes after the scene.
    std::vector<uint8_t> longer = bytes;
    longer.push_back(0);
    CHECK(!scenes::decodeImportResult(longer.data(), longer.size(), {}, &out, &importError, &error));
}
