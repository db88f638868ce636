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
