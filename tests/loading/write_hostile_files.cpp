// bricklight-hostile-files DIR: writes the cases of hostile_files.h under DIR and prints one line per
// case: name, tab, path to load, tab, the message regular expression, tab, "model" or "texture".
// bricklight-hostile-files --fuzz-seeds DIR: writes the fuzzers' seeds (tests/fuzz/seeds/ holds their
// output): DIR/model_import_fuzzer/ and DIR/image_import_fuzzer/, each file led by the byte that picks the
// format in that fuzzer (tests/fuzz/*_fuzzer.cpp).
#include <cstdio>
#include <filesystem>
#include <string>

#include "hostile_files.h"
#include "scene_geometry.h"
#include "scene_wire.h"

using namespace bricklight::testing;

namespace {

void seed(const std::string& dir, const std::string& name, int format, const std::string& bytes) {
    writeFile(dir + "/" + name, std::string(1, char(format)) + bytes);
}

void writeFuzzSeeds(const std::string& root) {
    namespace fs = std::filesystem;
    const std::string models = root + "/model_import_fuzzer", images = root + "/image_import_fuzzer";
    fs::create_directories(models);
    fs::create_directories(images);
    // Model formats: 0 obj, 1 ply, 2 gltf, 3 glb, 4 stl; 16: an importer reply. Second files follow "\n@@2@@\n".
    const std::string second = "\n@@2@@\n";
    seed(models, "triangle.obj", 0, objTriangle("model.mtl") + second + "newmtl m\nKd 1 0.5 0.25\nmap_Kd texture.png\n");
    seed(models, "long_texture_name.obj", 0, objTriangle("model.mtl") + second + "newmtl m\nmap_Kd " + std::string(5000, 'n') + ".png\n");
    seed(models, "texture_dev_zero.obj", 0, objTriangle("model.mtl") + second + "newmtl m\nmap_Kd /dev/zero\n");
    seed(models, "mtllib_outside.obj", 0, objTriangle("../../../etc/passwd"));
    seed(models, "texture_before_newmtl.obj", 0, objTriangle("model.mtl") + second + "map_Kd t.png\nnewmtl m\n");
    seed(models, "polygon.obj", 0, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\nf 1 2 3 4 5\nf 1 2 3\n");
    const std::string plyHeader = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    seed(models, "triangle_ascii.ply", 1, "ply\nformat ascii 1.0\n" + plyHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    seed(models, "face255_ascii.ply", 1, "ply\nformat ascii 1.0\n" + plyHeader + "0 0 0\n1 0 0\n0 1 0\n255 0 1 2\n");
    const std::string vertices = std::string("\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0", 36);
    const std::string indices = std::string("\0\0\0\0\1\0\0\0\2\0\0\0", 12);
    seed(models, "triangle_binary.ply", 1, "ply\nformat binary_little_endian 1.0\n" + plyHeader + vertices + "\x03" + indices);
    seed(models, "face255_binary.ply", 1, "ply\nformat binary_little_endian 1.0\n" + plyHeader + vertices + "\xFF" + indices);
    seed(models, "empty_face_binary.ply", 1, "ply\nformat binary_little_endian 1.0\n" + plyHeader + vertices + std::string(1, '\0'));
    seed(models, "plyly.ply", 1, "plyly\nformat ascii 1.0\nelement vertex 1\n");
    seed(models, "no_end_header.ply", 1, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n0 0 0\n1 0 0\n0 1 0\n");
    seed(models, "triangle.gltf", 2, gltfTriangle("texture.png", "buffer.bin") + second + triangleBuffer());
    seed(models, "buffer_outside.gltf", 2, gltfTriangle("texture.png", "../../../etc/passwd"));
    seed(models, "image_dev_zero.gltf", 2, gltfTriangle("/dev/zero", "buffer.bin") + second + triangleBuffer());
    seed(models, "deep_json.gltf", 2, gltfTriangle("texture.png", "buffer.bin", ",\"extras\":" + std::string(20000, '[') + std::string(20000, ']')));
    std::string nodes = "[";
    for (int i = 0; i < 999; ++i) nodes += "{\"children\":[" + std::to_string(i + 1) + "]},";
    nodes += "{\"mesh\":0}]";
    std::string deep = gltfTriangle("texture.png", "buffer.bin");
    deep.replace(deep.find("[{\"mesh\":0}]"), 12, nodes);
    seed(models, "deep_nodes.gltf", 2, deep + second + triangleBuffer());
    seed(models, "triangle.glb", 3, glbTriangle(pngBytes(2, 2, 2)));
    seed(models, "embedded_huge_png.glb", 3, glbTriangle(pngBytes(30000, 30000, 1).substr(0, 200)));
    std::string huge = "glTF" + std::string("\x02\0\0\0\xEC\x02\0\0\xF0\xFF\xFF\xFFJSON", 16) + "{\"asset\":{\"version\":\"2.0\"}}";
    seed(models, "huge_chunk.glb", 3, huge + std::string(748 - huge.size(), ' '));
    seed(models, "triangle.stl", 4, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
    bricklight::scenes::SceneGeometry scene;
    bricklight::scenes::TriangleMesh mesh;
    mesh.name = "triangle";
    mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    mesh.indices = {0, 1, 2};
    mesh.uvs = {0, 0, 1, 0, 0, 1};
    mesh.baseColorTexture = "model.glb*0.png";
    mesh.embeddedTexture = std::make_shared<std::vector<uint8_t>>(4, uint8_t(7));
    scene.meshes = {mesh, mesh};
    scene.meshes[1].alphaCutoff = 0.5f;  // the alpha test's fields, for the fuzzer to corrupt
    scene.meshes[1].baseAlpha = 0.75f;
    scene.meshes[1].alphaTexture = "leaf.png";
    scene.instances = {{0, glm::mat4(1.0f)}, {1, glm::mat4(2.0f)}};
    scene.pointLights.resize(1);
    scene.warnings = {"a warning"};
    const std::vector<uint8_t> reply = bricklight::scenes::encodeImportResult(scene, "");
    seed(models, "reply.bin", 16, std::string(reply.begin(), reply.end()));
    const std::vector<uint8_t> failure = bricklight::scenes::encodeImportResult({}, "'model.ply': an error");
    seed(models, "reply_error.bin", 16, std::string(failure.begin(), failure.end()));

    // Image formats: 0 png, 1 jpg, 2 tga, 3 bmp, 5 hdr, 9 pnm; +16: the bytes arrive as an embedded texture.
    for (int embedded : {0, 16}) {
        const std::string tag = embedded ? "_embedded" : "_file";
        seed(images, "grey" + tag + ".png", 0 + embedded, pngBytes(4, 4, 4));
        seed(images, "huge_header" + tag + ".png", 0 + embedded, pngBytes(30000, 30000, 0));
        seed(images, "cut" + tag + ".png", 0 + embedded, pngBytes(16, 16, 16).substr(0, 60));
        seed(images, "grey" + tag + ".pnm", 9 + embedded, "P6\n2 2\n255\n" + std::string(12, '\x80'));
        seed(images, "huge_header" + tag + ".pnm", 9 + embedded, "P6\n30000 30000\n255\n" + std::string(12, '\x80'));
        seed(images, "grey" + tag + ".hdr", 5 + embedded, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n" + std::string(16, '\x80'));
        // TGA: uncompressed true colour, 2 x 2, 24 bits, top-left origin.
        seed(images, "grey" + tag + ".tga", 2 + embedded,
             std::string("\0\0\x02\0\0\0\0\0\0\0\0\0\x02\0\x02\0\x18\x20", 18) + std::string(12, '\x80'));
        // BMP: 2 x 2, 24 bits, rows padded to 4 bytes.
        seed(images, "grey" + tag + ".bmp", 3 + embedded,
             std::string("BM\x46\0\0\0\0\0\0\0\x36\0\0\0\x28\0\0\0\x02\0\0\0\x02\0\0\0\x01\0\x18\0\0\0\0\0\x10\0\0\0\x13\x0b\0\0\x13\x0b\0\0\0\0\0\0\0\0\0\0",
                         54) +
                 std::string(16, '\x80'));
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 3 && std::string(argv[1]) == "--fuzz-seeds") {
        writeFuzzSeeds(argv[2]);
        return 0;
    }
    if (argc != 2) {
        std::fprintf(stderr, "usage: bricklight-hostile-files DIR | --fuzz-seeds DIR\n");
        return 2;
    }
    for (const auto& c : writeHostileFiles(argv[1]))
        std::printf("%s\t%s\t%s\t%s\n", c.name.c_str(), c.path.c_str(), c.message.c_str(), c.texture ? "texture" : "model");
    return 0;
}
