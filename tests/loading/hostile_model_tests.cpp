// Every hostile file of issue 23 through loadModel, out of process (the default) and in process: a clear
// message naming the file and the problem, within seconds, and this process still standing.
#include "test_support.h"

#include "hostile_files.h"
#include "scene_geometry.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

void refusesEveryHostileModel(bool isolate) {
    const std::string dir = freshFolder(isolate ? "hostile-isolated" : "hostile-in-process");
    scenes::LoadLimits limits;
    limits.isolateImport = isolate;
    for (const HostileFile& c : writeHostileFiles(dir)) {
        if (c.texture) continue;  // the model is fine: texture_tests.cpp
        INFO(c.name << ": " << c.what);
        std::string error;
        scenes::SceneGeometry s;
        const double seconds = secondsOf([&] { s = scenes::loadModel(c.path, &error, limits); });
        INFO("error: " << error << " (" << seconds << " s)");
        CHECK(s.meshes.empty());
        CHECK(matches(error, c.message));
        CHECK(matches(error, "^cannot load '"));
        CHECK(seconds < kMaxSeconds);
    }
}

}  // namespace

TEST_CASE("loading: hostile model files are refused quickly with a clear message (out of process)", "[loading]") {
    refusesEveryHostileModel(true);
}

TEST_CASE("loading: hostile model files are refused quickly with a clear message (in process)", "[loading]") {
    // The checks before assimp catch every known case, so even the unprotected path survives them.
    refusesEveryHostileModel(false);
}

TEST_CASE("loading: refusals over a limit name the option that raises it", "[loading]") {
    const std::string dir = freshFolder("hints");
    std::string error;
    for (const HostileFile& c : writeHostileFiles(dir)) {
        scenes::loadModel(c.path, &error);
        if (c.name == "gltf-deep-nodes") CHECK(matches(error, "--max-node-depth, LoadLimits::maxNodeDepth"));
        if (c.name == "gltf-deep-json") CHECK(matches(error, "--max-json-depth, LoadLimits::maxJsonDepth"));
        if (c.name == "gltf-buffer-outside") CHECK(matches(error, "allow it with --allow-outside-paths"));
    }
}

TEST_CASE("loading: what assimp crashes on, with the limits raised, is an error from the child process", "[loading]") {
    // The 30,000-deep node chain overflows assimp's stack once the depth check lets it through: the
    // crash stays in the importer's process.
    const std::string dir = freshFolder("crash");
    scenes::LoadLimits limits;
    limits.maxNodeDepth = 1000000;
    for (const HostileFile& c : writeHostileFiles(dir)) {
        if (c.name != "gltf-deep-nodes") continue;
        std::string error;
        scenes::SceneGeometry s;
        const double seconds = secondsOf([&] { s = scenes::loadModel(c.path, &error, limits); });
        INFO(error << " (" << seconds << " s)");
        CHECK(s.meshes.empty());
        CHECK(matches(error, "^cannot load '.*model\\.gltf': the model importer crashed \\(signal 11, "));
        CHECK(seconds < kMaxSeconds);
    }
}

TEST_CASE("loading: LoadLimits bound a valid model too", "[loading]") {
    const std::string dir = freshFolder("limits");
    writeFile(dir + "/model.obj", objTriangle("model.mtl"));
    writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\n");
    std::string error;
    REQUIRE(!scenes::loadModel(dir + "/model.obj", &error).meshes.empty());
    scenes::LoadLimits limits;
    limits.maxVertices = 2;
    CHECK(scenes::loadModel(dir + "/model.obj", &error, limits).meshes.empty());
    CHECK(matches(error, "model\\.obj': line 4: more than 2 vertices \\(raise it with --max-vertices"));
    limits = {};
    limits.maxFaceIndices = 2;
    CHECK(scenes::loadModel(dir + "/model.obj", &error, limits).meshes.empty());
    CHECK(matches(error, "a face of 3 corners, over the limit of 2"));
    limits = {};
    limits.maxFileBytes = 16;
    CHECK(scenes::loadModel(dir + "/model.obj", &error, limits).meshes.empty());
    CHECK(matches(error, "model\\.obj': it is [0-9]+ bytes, over the limit of 16 \\(raise it with --max-file-bytes"));
    // PLY: the header's counts are checked before the body is read.
    writeFile(dir + "/many.ply", "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n0\n");
    CHECK(scenes::loadModel(dir + "/many.ply", &error).meshes.empty());
    CHECK(matches(error, "element 'vertex' claims 4000000000 entries, more than the file's 2 bytes"));
    // glTF: a mesh placed by many nodes counts once per node (the importer copies it for each).
    std::string nodes = "[{\"children\":[";
    for (int i = 1; i <= 100; ++i) nodes += std::to_string(i) + (i < 100 ? "," : "");
    nodes += "]}";
    for (int i = 1; i <= 100; ++i) nodes += ",{\"mesh\":0}";
    nodes += "]";
    writeFile(dir + "/triangle.bin", triangleBuffer());
    std::string gltf = gltfTriangle("none.png", "triangle.bin");
    gltf.replace(gltf.find("[{\"mesh\":0}]"), 12, nodes);
    writeFile(dir + "/instanced.gltf", gltf);
    limits = {};
    REQUIRE(!scenes::loadModel(dir + "/instanced.gltf", &error, limits).meshes.empty());
    limits.maxVertices = 299;
    CHECK(scenes::loadModel(dir + "/instanced.gltf", &error, limits).meshes.empty());
    CHECK(matches(error, "its nodes place more than 299 vertices"));
}

TEST_CASE("loading: referenced files outside the model's folder load only when allowed", "[loading]") {
    const std::string dir = freshFolder("outside");
    std::filesystem::create_directories(dir + "/model");
    std::filesystem::create_directories(dir + "/shared");
    writeFile(dir + "/shared/triangle.bin", triangleBuffer());
    writeFile(dir + "/model/model.gltf", gltfTriangle("../shared/texture.png", "../shared/triangle.bin"));
    std::string error;
    CHECK(scenes::loadModel(dir + "/model/model.gltf", &error).meshes.empty());
    CHECK(matches(error, "shared/triangle\\.bin' \\(named by '.*model\\.gltf'\\) lies outside the model's folder"));
    scenes::LoadLimits limits;
    limits.allowOutsidePaths = true;
    const scenes::SceneGeometry s = scenes::loadModel(dir + "/model/model.gltf", &error, limits);
    INFO(error);
    REQUIRE(s.meshes.size() == 1);
    CHECK(matches(s.meshes[0].baseColorTexture, "model/\\.\\./shared/texture\\.png$"));
    // The texture alone outside: refused by the model loader too (assimp only names it).
    writeFile(dir + "/model/triangle.bin", triangleBuffer());
    writeFile(dir + "/model/texture-outside.gltf", gltfTriangle("../shared/texture.png", "triangle.bin"));
    CHECK(scenes::loadModel(dir + "/model/texture-outside.gltf", &error).meshes.empty());
    CHECK(matches(error, "base colour texture '.*shared/texture\\.png' \\(named by .*\\) lies outside the model's folder"));
}

TEST_CASE("loading: every GLB chunk must fit the file", "[loading]") {
    const std::string dir = freshFolder("glb-chunks");
    std::string glb = glbTriangle(pngBytes(2, 2, 2));
    std::string error;
    writeFile(dir + "/model.glb", glb);
    REQUIRE(!scenes::loadModel(dir + "/model.glb", &error).meshes.empty());
    // The BIN chunk (after the JSON chunk) claiming 0x7FFFFFF0 bytes.
    const uint32_t jsonLength = uint32_t(uint8_t(glb[12])) | uint32_t(uint8_t(glb[13])) << 8 | uint32_t(uint8_t(glb[14])) << 16;
    const size_t bin = 20 + jsonLength;
    glb.replace(bin, 4, std::string("\xF0\xFF\xFF\x7F", 4));
    writeFile(dir + "/bin.glb", glb);
    CHECK(scenes::loadModel(dir + "/bin.glb", &error).meshes.empty());
    CHECK(matches(error, "bin\\.glb': GLB chunk 1 claims 2147483632 bytes but only [0-9]+ follow"));
    // A header claiming more than the file holds.
    glb = glbTriangle(pngBytes(2, 2, 2));
    glb.replace(8, 4, std::string("\0\0\0\x10", 4));
    writeFile(dir + "/length.glb", glb);
    CHECK(scenes::loadModel(dir + "/length.glb", &error).meshes.empty());
    CHECK(matches(error, "its GLB header claims 268435456 bytes but the file holds"));
}

TEST_CASE("loading: fuzzing finds in assimp, refused before it runs", "[loading]") {
    // model_import_fuzzer (in process): assimp 5.2's MTL reader crashes (SIGSEGV) on some statements
    // before any newmtl ("map_Kd", "bump", "a": all 11 crashing inputs of two runs). Out of process that
    // is "the model importer crashed"; the MTL check refuses it first, so that the unprotected in-process
    // path survives it too.
    // assimp aborts (an assertion in its triangulation) on a PLY face without indices.
    const std::string plyHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string emptyFaceDir = freshFolder("fuzz-finds-empty-face");
    writeFile(emptyFaceDir + "/empty_face.ply", plyHeader + "0\n");
    for (bool isolate : {true, false}) {
        scenes::LoadLimits limits;
        limits.isolateImport = isolate;
        std::string error;
        CHECK(scenes::loadModel(emptyFaceDir + "/empty_face.ply", &error, limits).meshes.empty());
        CHECK(matches(error, "empty_face\\.ply': face 1 lists no vertex indices"));
    }
    // And assimp's PLY reader spins (timed out) on a file that starts "plyly".
    const std::string dir = freshFolder("fuzz-finds");
    writeFile(dir + "/spin.ply", "plyly\nformat ascii 1.0\nelement vertex 1\n");
    writeFile(dir + "/spin.dat", "plyly\nformat ascii 1.0\nelement vertex 1\n");
    for (const char* name : {"spin.ply", "spin.dat"})
        for (bool isolate : {true, false}) {
            scenes::LoadLimits limits;
            limits.isolateImport = isolate;
            std::string error;
            const double seconds = secondsOf([&] { CHECK(scenes::loadModel(dir + "/" + name, &error, limits).meshes.empty()); });
            CHECK(matches(error, "spin\\.(ply|dat)': not a PLY file \\(no 'ply' line first\\)"));
            CHECK(seconds < kMaxSeconds);
        }
    writeFile(dir + "/model.obj", objTriangle("model.mtl"));
    for (const char* statement : {"map_Kd t.png", "bump t.png", "a"}) {
        writeFile(dir + "/model.mtl", std::string(statement) + "\nnewmtl m\n");
        for (bool isolate : {true, false}) {
            scenes::LoadLimits limits;
            limits.isolateImport = isolate;
            std::string error;
            CHECK(scenes::loadModel(dir + "/model.obj", &error, limits).meshes.empty());
            CHECK(matches(error, "model\\.mtl' line 1: '(map_Kd|bump|a)' before any newmtl"));
        }
    }
}
