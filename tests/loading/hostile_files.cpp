#include "hostile_files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

namespace bricklight::testing {

namespace {

std::string u32le(uint32_t v) { return {char(v & 0xFF), char((v >> 8) & 0xFF), char((v >> 16) & 0xFF), char(v >> 24)}; }
std::string u32be(uint32_t v) { return {char(v >> 24), char((v >> 16) & 0xFF), char((v >> 8) & 0xFF), char(v & 0xFF)}; }

uint32_t crc32(const std::string& bytes) {  // PNG's chunk checksum (ISO 3309)
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

std::string pngChunk(const std::string& type, const std::string& data) {
    return u32be(uint32_t(data.size())) + type + data + u32be(crc32(type + data));
}

// zlib data of stored (uncompressed) deflate blocks: no compressor needed.
std::string zlibStored(const std::string& raw) {
    std::string out = "\x78\x01";
    size_t pos = 0;
    do {
        const size_t n = std::min<size_t>(raw.size() - pos, 65535);
        const bool last = pos + n == raw.size();
        out += char(last ? 1 : 0);
        out += char(n & 0xFF);
        out += char(n >> 8);
        out += char(~n & 0xFF);
        out += char((~n >> 8) & 0xFF);
        out += raw.substr(pos, n);
        pos += n;
    } while (pos < raw.size());
    uint32_t a = 1, b = 0;
    for (unsigned char c : raw) {
        a = (a + c) % 65521;
        b = (b + a) % 65521;
    }
    return out + u32be((b << 16) | a);
}

std::string floats(std::initializer_list<float> values) {
    std::string out;
    for (float f : values) {
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        out += u32le(bits);
    }
    return out;
}

// The glTF of a textured triangle; `image` and `buffer` are the JSON objects of its one image and buffer,
// `moreViews` buffer views after the triangle's three, `nodes`/`sceneNodes` replace its one node.
std::string gltfJson(const std::string& image, const std::string& buffer, const std::string& moreViews = "",
                     const std::string& nodes = R"([{"mesh":0}])", const std::string& extraTopLevel = "") {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes +
           R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,"material":0}]}],)"
           R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],"textures":[{"source":0}],"images":[)" +
           image + R"(],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
           R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"},{"bufferView":2,"componentType":5123,"count":3,"type":"SCALAR"}],)"
           R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24},)"
           R"({"buffer":0,"byteOffset":60,"byteLength":6})" +
           moreViews + R"(],"buffers":[)" + buffer + "]" + extraTopLevel + "}";
}

}  // namespace

bool writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return bool(out);
}

std::string pngBytes(uint32_t width, uint32_t height, uint32_t rows) {
    std::string raw;
    for (uint32_t y = 0; y < rows; ++y) raw += '\0' + std::string(size_t(width) * 3, '\x80');  // filter 0, grey
    const std::string header = u32be(width) + u32be(height) + std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB
    return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", header) + pngChunk("IDAT", zlibStored(raw)) + pngChunk("IEND", "");
}

std::string triangleBuffer() {
    return floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) + floats({0, 0, 1, 0, 0, 1}) + std::string("\x00\x00\x01\x00\x02\x00\x00\x00", 8);
}

std::string gltfTriangle(const std::string& textureUri, const std::string& bufferUri, const std::string& extraTopLevel) {
    return gltfJson(R"({"uri":")" + textureUri + R"("})", R"({"uri":")" + bufferUri + R"(","byteLength":68})", "", R"([{"mesh":0}])",
                    extraTopLevel);
}

std::string glbTriangle(const std::string& png) {
    const std::string bin = triangleBuffer() + png + std::string((4 - png.size() % 4) % 4, '\0');
    std::string json = gltfJson(R"({"bufferView":3,"mimeType":"image/png"})", R"({"byteLength":)" + std::to_string(bin.size()) + "}",
                                R"(,{"buffer":0,"byteOffset":68,"byteLength":)" + std::to_string(png.size()) + "}");
    json += std::string((4 - json.size() % 4) % 4, ' ');
    const std::string chunks = u32le(uint32_t(json.size())) + "JSON" + json + u32le(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
    return "glTF" + u32le(2) + u32le(uint32_t(12 + chunks.size())) + chunks;
}

std::string objTriangle(const std::string& mtl) {
    return "mtllib " + mtl + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n";
}

std::vector<HostileFile> writeHostileFiles(const std::string& root) {
    namespace fs = std::filesystem;
    std::vector<HostileFile> cases;
    auto folder = [&](const std::string& name) {
        const std::string dir = root + "/" + name;
        fs::remove_all(dir);
        fs::create_directories(dir);
        return dir;
    };
    auto add = [&](const std::string& name, const std::string& path, const std::string& message, const std::string& what, bool texture = false) {
        cases.push_back({name, path, message, what, texture});
    };
    const std::string plyHeader = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    {
        const std::string dir = folder("ply-face255-binary");
        writeFile(dir + "/model.ply", "ply\nformat binary_little_endian 1.0\n" + plyHeader + floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) + "\xFF" +
                                          u32le(0) + u32le(1) + u32le(2));
        add("ply-face255-binary", dir + "/model.ply", "face 0 lists 255 values but the file ends", "binary PLY face claiming 255 indices, holding 3");
    }
    {
        const std::string dir = folder("ply-face255-ascii");
        writeFile(dir + "/model.ply", "ply\nformat ascii 1.0\n" + plyHeader + "0 0 0\n1 0 0\n0 1 0\n255 0 1 2\n");
        add("ply-face255-ascii", dir + "/model.ply", "face 0 lists 255 values but its line holds 3", "ASCII PLY face claiming 255 indices, holding 3");
    }
    {
        const std::string dir = folder("ply-no-end-header");
        writeFile(dir + "/model.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                      "0 0 0\n1 0 0\n0 1 0\n");
        add("ply-no-end-header", dir + "/model.ply", "no end_header line", "PLY header without end_header");
    }
    {
        const std::string dir = folder("gltf-deep-nodes");
        std::string nodes = "[";
        const int depth = 30000;
        for (int i = 0; i + 1 < depth; ++i) nodes += R"({"children":[)" + std::to_string(i + 1) + "]},";
        nodes += R"({"mesh":0}])";
        writeFile(dir + "/triangle.bin", triangleBuffer());
        writeFile(dir + "/model.gltf", gltfJson(R"({"uri":"texture.png"})", R"({"uri":"triangle.bin","byteLength":68})", "", nodes));
        writeFile(dir + "/texture.png", pngBytes(2, 2, 2));
        add("gltf-deep-nodes", dir + "/model.gltf", "node hierarchy is more than 256 levels deep", "glTF with a 30,000-deep node chain");
    }
    {
        const std::string dir = folder("gltf-deep-json");
        const size_t depth = 1000000;
        writeFile(dir + "/triangle.bin", triangleBuffer());
        writeFile(dir + "/texture.png", pngBytes(2, 2, 2));
        writeFile(dir + "/model.gltf", gltfTriangle("texture.png", "triangle.bin",
                                                   R"(,"extras":)" + std::string(depth, '[') + std::string(depth, ']')));
        add("gltf-deep-json", dir + "/model.gltf", "JSON nests more than 128 levels deep", "glTF whose JSON nests 1,000,000 deep");
    }
    {
        const std::string dir = folder("glb-huge-chunk");
        std::string glb = "glTF" + u32le(2) + u32le(748) + u32le(0xFFFFFFF0u) + "JSON" + R"({"asset":{"version":"2.0"}})";
        glb += std::string(748 - glb.size(), ' ');
        writeFile(dir + "/model.glb", glb);
        add("glb-huge-chunk", dir + "/model.glb", "claims 4294967280 bytes", "748-byte GLB whose JSON chunk claims 0xFFFFFFF0 bytes");
    }
    {
        const std::string dir = folder("obj-texture-dev-zero");
        writeFile(dir + "/model.obj", objTriangle("model.mtl"));
        writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\nmap_Kd /dev/zero\n");
        add("obj-texture-dev-zero", dir + "/model.obj", "'/dev/zero' .*lies outside the model's folder", "OBJ whose map_Kd is /dev/zero");
    }
    {
        const std::string dir = folder("obj-texture-link-to-dev-zero");
        writeFile(dir + "/model.obj", objTriangle("model.mtl"));
        writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\nmap_Kd zero.png\n");
        fs::create_symlink("/dev/zero", dir + "/zero.png");
        add("obj-texture-link-to-dev-zero", dir + "/model.obj", "zero\\.png' .*lies outside the model's folder",
            "OBJ whose map_Kd is a link (in its folder) to /dev/zero");
    }
    {
        const std::string dir = folder("gltf-image-dev-zero");
        writeFile(dir + "/triangle.bin", triangleBuffer());
        writeFile(dir + "/model.gltf", gltfTriangle("/dev/zero", "triangle.bin"));
        add("gltf-image-dev-zero", dir + "/model.gltf", "'/dev/zero' .*lies outside the model's folder", "glTF whose image URI is /dev/zero");
    }
    const std::string hugePng = pngBytes(30000, 30000, 1);  // the header claims 900 Mpixels; 1 row of data
    const std::string hugeMessage = "30000 x 30000 pixels, over the limit of 67108864";
    {
        const std::string dir = folder("obj-texture-huge-png");
        writeFile(dir + "/model.obj", objTriangle("model.mtl"));
        writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\nmap_Kd huge.png\n");
        writeFile(dir + "/huge.png", hugePng);
        add("obj-texture-huge-png", dir + "/model.obj", hugeMessage, "OBJ texture: PNG claiming 30000 x 30000", true);
    }
    {
        const std::string dir = folder("gltf-image-huge-png");
        writeFile(dir + "/triangle.bin", triangleBuffer());
        writeFile(dir + "/model.gltf", gltfTriangle("huge.png", "triangle.bin"));
        writeFile(dir + "/huge.png", hugePng);
        add("gltf-image-huge-png", dir + "/model.gltf", hugeMessage, "glTF image: PNG claiming 30000 x 30000", true);
    }
    {
        const std::string dir = folder("glb-embedded-huge-png");
        writeFile(dir + "/model.glb", glbTriangle(hugePng));
        add("glb-embedded-huge-png", dir + "/model.glb", hugeMessage, "GLB embedding a PNG claiming 30000 x 30000", true);
    }
    const std::string longName(5000, 'n');
    {
        const std::string dir = folder("obj-long-texture-name");
        writeFile(dir + "/model.obj", objTriangle("model.mtl"));
        writeFile(dir + "/model.mtl", "newmtl m\nKd 1 1 1\nmap_Kd " + longName + ".png\n");
        add("obj-long-texture-name", dir + "/model.obj", "texture name is 5004 characters; assimp keeps at most 1023",
            "MTL texture name of 5004 characters");
    }
    {
        const std::string dir = folder("gltf-long-image-uri");
        writeFile(dir + "/triangle.bin", triangleBuffer());
        writeFile(dir + "/model.gltf", gltfTriangle(longName + ".png", "triangle.bin"));
        add("gltf-long-image-uri", dir + "/model.gltf", "file name is 5004 characters; assimp keeps at most 1023",
            "glTF image URI of 5004 characters");
    }
    {
        const std::string dir = folder("gltf-buffer-outside");
        std::string up;
        for (int i = 0; i < 32; ++i) up += "../";  // past the root from any test folder (".." of "/" is "/")
        writeFile(dir + "/texture.png", pngBytes(2, 2, 2));
        writeFile(dir + "/model.gltf", gltfTriangle("texture.png", up + "etc/passwd"));
        add("gltf-buffer-outside", dir + "/model.gltf", "etc/passwd' .*lies outside the model's folder", "glTF buffer URI ../../../etc/passwd");
    }
    {
        const std::string dir = folder("fifo-model");
        mkfifo((dir + "/model.obj").c_str(), 0600);
        add("fifo-model", dir + "/model.obj", "is a FIFO, not a regular file", "a FIFO as the model");
    }
    {
        const std::string dir = folder("directory-model");
        fs::create_directories(dir + "/model.obj");
        add("directory-model", dir + "/model.obj", "is a directory, not a regular file", "a directory as the model");
    }
    return cases;
}

}  // namespace bricklight::testing
