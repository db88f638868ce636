// Valid models still load under the default limits, out of process and in process alike: a handful of
// Debian's assimp test models (assimp-testmodels, installed by scripts/bootstrap.sh) and the valid
// triangles the hostile cases are made from.
#include "test_support.h"

#include "hostile_files.h"
#include "scene_geometry.h"
#if defined(BRICKLIGHT_TEST_TEXTURES)
#include "texture_loader.h"
#endif

using namespace bricklight;
using namespace bricklight::testing;

namespace {

uint64_t triangles(const scenes::SceneGeometry& s) { return s.triangleCount(); }

void sameScene(const scenes::SceneGeometry& a, const scenes::SceneGeometry& b) {
    REQUIRE(a.meshes.size() == b.meshes.size());
    CHECK(triangles(a) == triangles(b));
    CHECK(a.pointLights.size() == b.pointLights.size());
    CHECK(a.warnings == b.warnings);
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        CHECK(a.meshes[i].positions == b.meshes[i].positions);
        CHECK(a.meshes[i].indices == b.meshes[i].indices);
        CHECK(a.meshes[i].baseColorTexture == b.meshes[i].baseColorTexture);
        CHECK(bool(a.meshes[i].embeddedTexture) == bool(b.meshes[i].embeddedTexture));
        if (a.meshes[i].embeddedTexture && b.meshes[i].embeddedTexture) CHECK(*a.meshes[i].embeddedTexture == *b.meshes[i].embeddedTexture);
    }
}

#if defined(BRICKLIGHT_TEST_TEXTURES)
void texturesLoad(const scenes::SceneGeometry& s) {
    for (const auto& m : s.meshes) {
        if (m.baseColorTexture.empty()) continue;
        std::vector<uint8_t> texels;
        std::string error;
        INFO(m.baseColorTexture);
        CHECK(render::loadTextureLayer(m.baseColorTexture, 8, &texels, &error, m.embeddedTexture.get(), s.loadLimits));
        INFO(error);
    }
}
#else
void texturesLoad(const scenes::SceneGeometry&) {}
#endif

}  // namespace

TEST_CASE("loading: assimp's test models load, the same in and out of process", "[loading]") {
    const std::string root = BRICKLIGHT_ASSIMP_MODELS;
    const struct {
        const char* path;
        uint64_t triangles;  // 0: any number above 0
        bool textured;
    } models[] = {
        {"glTF2/BoxTextured-glTF/BoxTextured.gltf", 12, true},
        {"glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", 12, true},
        {"glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf", 12, true},
        {"glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", 0, false},
        {"OBJ/spider.obj", 0, true},
        {"OBJ/box.obj", 12, false},
        {"PLY/Wuson.ply", 0, false},
        {"PLY/cube_binary.ply", 12, false},
        {"Collada/lights.dae", 0, false},
        {"STL/Spider_ascii.stl", 0, false},
    };
    for (const auto& m : models) {
        const std::string path = root + "/" + m.path;
        INFO(path);
        std::string error;
        scenes::SceneGeometry isolated;
        const double seconds = secondsOf([&] { isolated = scenes::loadModel(path, &error); });
        INFO(error << " (" << seconds << " s)");
        REQUIRE(!isolated.meshes.empty());
        if (m.triangles) CHECK(triangles(isolated) == m.triangles);
        bool textured = false;
        for (const auto& mesh : isolated.meshes) textured |= !mesh.baseColorTexture.empty();
        CHECK(textured == m.textured);
        scenes::LoadLimits inProcess;
        inProcess.isolateImport = false;
        const scenes::SceneGeometry direct = scenes::loadModel(path, &error, inProcess);
        REQUIRE(!direct.meshes.empty());
        sameScene(isolated, direct);
        texturesLoad(isolated);
    }
}

TEST_CASE("loading: the valid triangles the hostile cases are made from load with their textures", "[loading]") {
    const std::string dir = freshFolder("valid");
    writeFile(dir + "/texture.png", pngBytes(4, 4, 4));
    writeFile(dir + "/triangle.bin", triangleBuffer());
    writeFile(dir + "/model.gltf", gltfTriangle("texture.png", "triangle.bin"));
    writeFile(dir + "/model.glb", glbTriangle(pngBytes(4, 4, 4)));
    writeFile(dir + "/model.obj", objTriangle("model.mtl"));
    writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\nmap_Kd texture.png\n");
    writeFile(dir + "/model.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    for (const char* name : {"model.gltf", "model.glb", "model.obj", "model.ply"}) {
        INFO(name);
        std::string error;
        const scenes::SceneGeometry s = scenes::loadModel(dir + "/" + name, &error);
        INFO(error);
        REQUIRE(s.meshes.size() == 1);
        CHECK(triangles(s) == 1);
        if (std::string(name) != "model.ply") {
            CHECK(!s.meshes[0].baseColorTexture.empty());
            CHECK(bool(s.meshes[0].embeddedTexture) == (std::string(name) == "model.glb"));
        }
        texturesLoad(s);
    }
}

namespace {

// gltfTriangle with `material` as its one material.
std::string gltfWithMaterial(const std::string& material) {
    std::string json = gltfTriangle("texture.png", "triangle.bin");
    const std::string plain = R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}])";
    const size_t at = json.find(plain);
    REQUIRE(at != std::string::npos);
    return json.replace(at, plain.size(), R"("materials":[)" + material + "]");
}

}  // namespace

TEST_CASE("loading: alpha-tested materials (glTF alphaMode and alphaCutoff, OBJ map_d) come through", "[loading]") {
    const std::string dir = freshFolder("alpha");
    writeFile(dir + "/texture.png", pngBytes(4, 4, 4));
    writeFile(dir + "/triangle.bin", triangleBuffer());
    const std::string texture = R"("baseColorTexture":{"index":0})";
    const struct {
        const char* name;
        std::string material;
        float cutoff, baseAlpha;
        const char* warning;  // "" none
    } gltf[] = {
        {"mask", R"({"alphaMode":"MASK","alphaCutoff":0.3,"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.75],)" + texture + "}}", 0.3f, 0.75f, ""},
        {"mask-default", R"({"alphaMode":"MASK","pbrMetallicRoughness":{)" + texture + "}}", 0.5f, 1.0f, ""},
        {"opaque", R"({"alphaMode":"OPAQUE","alphaCutoff":0.3,"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.25],)" + texture + "}}", 0.0f, 1.0f, ""},
        {"blend", R"({"alphaMode":"BLEND","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.5],)" + texture + "}}", 0.5f, 0.5f,
         "alphaMode BLEND is drawn as MASK with a cut-off of 0.5"},
        {"negative", R"({"alphaMode":"MASK","alphaCutoff":-0.5,"pbrMetallicRoughness":{)" + texture + "}}", 0.0f, 1.0f,
         "alphaCutoff -0.500000 is outside \\[0, 1\\]; clamped"},
        {"over-one", R"({"alphaMode":"MASK","alphaCutoff":7,"pbrMetallicRoughness":{)" + texture + "}}", 1.0f, 1.0f,
         "alphaCutoff 7.000000 is outside \\[0, 1\\]; clamped"},
        {"factor-over-one", R"({"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,3],)" + texture + "}}", 0.5f, 1.0f,
         "the base colour factor's alpha 3.000000 is outside \\[0, 1\\]; clamped"},
    };
    for (const auto& c : gltf) {
        INFO(c.name);
        const std::string path = dir + "/" + c.name + ".gltf";
        writeFile(path, gltfWithMaterial(c.material));
        for (bool isolate : {true, false}) {
            scenes::LoadLimits limits;
            limits.isolateImport = isolate;
            std::string error;
            const scenes::SceneGeometry s = scenes::loadModel(path, &error, limits);
            INFO(error);
            REQUIRE(s.meshes.size() == 1);
            CHECK(s.meshes[0].alphaCutoff == c.cutoff);
            CHECK(s.meshes[0].baseAlpha == c.baseAlpha);
            CHECK(s.meshes[0].alphaTexture.empty());  // the base colour texture's alpha
            CHECK(!s.meshes[0].baseColorTexture.empty());
            bool warned = false;
            for (const std::string& w : s.warnings) warned |= *c.warning && matches(w, c.warning);
            CHECK(warned == (*c.warning != 0));
        }
    }
    // A cut-off that is not a finite number (NaN, 1e999) is refused: the JSON checks before assimp catch both; the
    // importer checks again for what assimp might hand over.
    writeFile(dir + "/nan.gltf", gltfWithMaterial(R"({"alphaMode":"MASK","alphaCutoff":NaN,"pbrMetallicRoughness":{)" + texture + "}}"));
    writeFile(dir + "/inf.gltf", gltfWithMaterial(R"({"alphaMode":"MASK","alphaCutoff":1e999,"pbrMetallicRoughness":{)" + texture + "}}"));
    std::string error;
    CHECK(scenes::loadModel(dir + "/nan.gltf", &error).meshes.empty());
    CHECK(matches(error, "^cannot load '.*nan.gltf'"));
    CHECK(scenes::loadModel(dir + "/inf.gltf", &error).meshes.empty());
    CHECK(matches(error, "^cannot load '.*inf.gltf'"));
    // What assimp would make opaque without a word: an alphaMode that is not one of glTF's three names (they are
    // case-sensitive), a cut-off that is not a number.
    const struct {
        const char* name;
        std::string material, message;
    } refused[] = {
        {"lower-case", R"({"alphaMode":"mask"})", R"(material 0's alphaMode "mask" is not "OPAQUE", "MASK" or "BLEND")"},
        {"cutout", R"({"alphaMode":"CUTOUT"})", R"(material 0's alphaMode "CUTOUT" is not)"},
        {"number", R"({"alphaMode":1})", "material 0's alphaMode 1 is not"},
        {"empty", R"({"alphaMode":""})", R"(material 0's alphaMode "" is not)"},
        {"cutoff-string", R"({"alphaMode":"MASK","alphaCutoff":"half"})", R"(material 0's alphaCutoff "half" is not a number)"},
    };
    for (const auto& c : refused) {
        INFO(c.name);
        writeFile(dir + "/refused.gltf", gltfWithMaterial(c.material));
        CHECK(scenes::loadModel(dir + "/refused.gltf", &error).meshes.empty());
        INFO(error);
        CHECK(error.find(c.message) != std::string::npos);
    }
    // An image whose uri is empty: assimp drops the texture without a word.
    writeFile(dir + "/empty_uri.gltf", gltfTriangle("", "triangle.bin"));
    CHECK(scenes::loadModel(dir + "/empty_uri.gltf", &error).meshes.empty());
    CHECK(error.find("image 0's uri is empty (neither a file nor data)") != std::string::npos);

    // OBJ: map_d is the coverage, tested at 0.5; without it the mesh is opaque.
    writeFile(dir + "/model.obj", objTriangle("model.mtl"));
    writeFile(dir + "/leaf.png", pngBytes(4, 4, 4));
    writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\nmap_Kd texture.png\nmap_d leaf.png\n");
    scenes::SceneGeometry s = scenes::loadModel(dir + "/model.obj", &error);
    INFO(error);
    REQUIRE(s.meshes.size() == 1);
    CHECK(s.meshes[0].alphaCutoff == 0.5f);
    CHECK(s.meshes[0].baseAlpha == 1.0f);
    CHECK(s.meshes[0].alphaTexture == dir + "/leaf.png");
    CHECK(s.meshes[0].baseColorTexture == dir + "/texture.png");
    writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\nmap_Kd texture.png\n");
    s = scenes::loadModel(dir + "/model.obj", &error);
    REQUIRE(s.meshes.size() == 1);
    CHECK(s.meshes[0].alphaCutoff == 0.0f);
    CHECK(s.meshes[0].alphaTexture.empty());
    // An opacity map outside the model's folder is refused like a base colour texture there.
    writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\nmap_d ../../outside.png\n");
    CHECK(scenes::loadModel(dir + "/model.obj", &error).meshes.empty());
    CHECK(matches(error, "its opacity map '.*outside.png' \\(named by .*\\) lies outside the model's folder"));
}

TEST_CASE("loading: a file without lights gets a sky and a sun unless its surfaces emit", "[loading]") {
    const std::string dir = freshFolder("lit-by-itself");
    writeFile(dir + "/model.obj", objTriangle("model.mtl"));
    for (bool emissive : {false, true}) {
        INFO(emissive);
        writeFile(dir + "/model.mtl", std::string("newmtl m\nKd 0.5 0.5 0.5\n") + (emissive ? "Ke 4 3 2\n" : ""));
        for (bool isolate : {true, false}) {
            scenes::LoadLimits limits;
            limits.isolateImport = isolate;
            std::string error;
            const scenes::SceneGeometry s = scenes::loadModel(dir + "/model.obj", &error, limits);
            INFO(error);
            REQUIRE(s.meshes.size() == 1);
            CHECK((s.meshes[0].emission == glm::vec3(4.0f, 3.0f, 2.0f)) == emissive);
            CHECK((glm::length(s.environment.skyRadiance) > 0.0f) == !emissive);
            CHECK((glm::length(s.environment.sunIrradiance) > 0.0f) == !emissive);
        }
    }
}

#if defined(BRICKLIGHT_TEST_TEXTURES)
TEST_CASE("loading: an opacity map without alpha gives its first channel as the coverage", "[loading]") {
    const std::string dir = freshFolder("coverage");
    writeFile(dir + "/grey.png", pngBytes(4, 4, 4));  // RGB, every channel 0x80
    std::vector<uint8_t> colour, coverage;
    std::string error;
    REQUIRE(render::loadTextureLayer(dir + "/grey.png", 4, &colour, &error));
    REQUIRE(render::loadTextureLayer(dir + "/grey.png", 4, &coverage, &error, nullptr, {}, true));
    REQUIRE(colour.size() == 64);
    REQUIRE(coverage.size() == 64);
    CHECK(colour[3] == 255);     // a base colour texture without alpha is opaque
    CHECK(coverage[3] == 0x80);  // as a coverage map, its grey is the alpha
    CHECK(coverage[0] == 0x80);
}
#endif
