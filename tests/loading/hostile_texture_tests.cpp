// Textures that models name, through the renderer's texture loader: a header over the pixel budget is
// refused before decoding, /dev/zero, FIFOs and directories are refused before OpenImageIO probes them.
#include "test_support.h"

#include <sys/stat.h>

#include <cmath>

#include "hostile_files.h"
#include "scene_geometry.h"
#include "texture_loader.h"

using namespace bricklight;
using namespace bricklight::testing;

// OpenImageIO 2.4 leaks an error string (allocated in ImageInput::geterror, called inside the library)
// when a reader fails on a broken image; LeakSanitizer would fail the sanitizer build on that third-party
// leak. Read by LeakSanitizer only (the name is its hook); other builds never call it.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOpenImageIO.so\n"; }

namespace {

// The first mesh's base colour texture through the loader, under the limits the scene was loaded with.
bool loadFirstTexture(const scenes::SceneGeometry& s, std::string* error, double* seconds) {
    std::vector<uint8_t> texels;
    bool ok = false;
    *seconds = secondsOf([&] {
        ok = render::loadTextureLayer(s.meshes[0].baseColorTexture, 16, &texels, error, s.meshes[0].embeddedTexture.get(), s.loadLimits);
    });
    return ok;
}

}  // namespace

TEST_CASE("loading: hostile textures are refused from their header, quickly", "[loading]") {
    const std::string dir = freshFolder("hostile-textures");
    for (const HostileFile& c : writeHostileFiles(dir)) {
        if (!c.texture) continue;
        INFO(c.name << ": " << c.what);
        std::string error;
        const scenes::SceneGeometry s = scenes::loadModel(c.path, &error);
        INFO(error);
        REQUIRE(s.meshes.size() == 1);
        double seconds = 0;
        CHECK(!loadFirstTexture(s, &error, &seconds));
        INFO("texture error: " << error << " (" << seconds << " s)");
        CHECK(matches(error, c.message));
        CHECK(matches(error, "raise it with --max-texture-pixels"));
        CHECK(seconds < 2.0);
    }
}

TEST_CASE("loading: /dev/zero as a texture is refused even where outside paths are allowed", "[loading]") {
    const std::string dir = freshFolder("dev-zero");
    scenes::LoadLimits limits;
    limits.allowOutsidePaths = true;
    int checked = 0;
    for (const HostileFile& c : writeHostileFiles(dir)) {
        if (c.name.find("dev-zero") == std::string::npos) continue;
        INFO(c.name);
        std::string error;
        const scenes::SceneGeometry s = scenes::loadModel(c.path, &error, limits);
        INFO(error);
        REQUIRE(s.meshes.size() == 1);
        double seconds = 0;
        CHECK(!loadFirstTexture(s, &error, &seconds));
        CHECK(matches(error, "' cannot be loaded: it is a device, not a regular file: refused"));
        CHECK(seconds < 1.0);
        ++checked;
    }
    CHECK(checked == 3);
}

TEST_CASE("loading: the texture loader refuses FIFOs, directories and missing files, and reads valid PNGs", "[loading]") {
    const std::string dir = freshFolder("texture-kinds");
    std::vector<uint8_t> texels;
    std::string error;
    REQUIRE(mkfifo((dir + "/fifo.png").c_str(), 0600) == 0);
    CHECK(!render::loadTextureLayer(dir + "/fifo.png", 4, &texels, &error));
    CHECK(matches(error, "fifo\\.png' cannot be loaded: it is a FIFO"));
    std::filesystem::create_directories(dir + "/folder.png");
    CHECK(!render::loadTextureLayer(dir + "/folder.png", 4, &texels, &error));
    CHECK(matches(error, "folder\\.png' cannot be loaded: it is a directory"));
    CHECK(!render::loadTextureLayer(dir + "/missing.png", 4, &texels, &error));
    CHECK(matches(error, "missing\\.png' cannot be loaded: No such file"));
    CHECK(texels.empty());
    // Valid: 2 x 2 grey, resampled to 4 x 4 RGBA.
    writeFile(dir + "/grey.png", pngBytes(2, 2, 2));
    REQUIRE(render::loadTextureLayer(dir + "/grey.png", 4, &texels, &error));
    REQUIRE(texels.size() == 4 * 4 * 4);
    CHECK(int(texels[0]) == 0x80);
    CHECK(int(texels[3]) == 255);
    // The budget is the header's width x height: a 2 x 2 image under a budget of 3 pixels is refused.
    scenes::LoadLimits limits;
    limits.maxTexturePixels = 3;
    CHECK(!render::loadTextureLayer(dir + "/grey.png", 4, &texels, &error, nullptr, limits));
    CHECK(matches(error, "it is 2 x 2 pixels, over the limit of 3"));
    // A cut-short image and bytes that are no image: errors, not crashes.
    const std::string png = pngBytes(64, 64, 64);
    writeFile(dir + "/cut.png", png.substr(0, png.size() / 2));
    CHECK(!render::loadTextureLayer(dir + "/cut.png", 4, &texels, &error));
    const std::vector<uint8_t> noise(300, 0x5A);
    CHECK(!render::loadTextureLayer("noise.png", 4, &texels, &error, &noise));
    CHECK(texels.size() == 4 * 4 * 4);  // the failures appended nothing
    // A float image (PFM: RGB floats) with a NaN and an infinity is refused, naming how many values; finite, it loads.
    auto pfm = [](const std::vector<float>& rgb) {
        std::string bytes = "PF\n2 2\n-1.0\n";
        bytes.append(reinterpret_cast<const char*>(rgb.data()), rgb.size() * sizeof(float));
        return bytes;
    };
    std::vector<float> values(12, 0.5f);
    writeFile(dir + "/finite.pfm", pfm(values));
    CHECK(render::loadTextureLayer(dir + "/finite.pfm", 4, &texels, &error));
    values[4] = std::nanf("");
    values[9] = INFINITY;
    writeFile(dir + "/nan.pfm", pfm(values));
    CHECK(!render::loadTextureLayer(dir + "/nan.pfm", 4, &texels, &error));
    CHECK(matches(error, "nan\\.pfm' cannot be loaded: it holds 2 values that are not finite \\(NaN or infinite\\) of 12"));
}
