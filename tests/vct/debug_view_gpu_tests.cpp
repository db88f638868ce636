// vct::Clipmap::debugView on both backends: looking at the emissive test cube's +Z face, the centre pixel shows
// the voxel's opacity along z only, the light it sends back (tone-mapped), its level, and that this update
// rewrote it; bad descriptions are refused.
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "test_device.h"
#include "voxelize_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

glm::u8vec4 centrePixel(TestDevice& td, vct::Clipmap& clipmap, vct::DebugViewDesc d, rhi::TextureHandle output) {
    Error error;
    d.output = output;
    INFO(error.message);
    REQUIRE(clipmap.debugView(d, &error));
    std::vector<glm::u8vec4> pixels(32 * 32);
    REQUIRE(td.device->readTexture(output, {}, pixels.data()));
    return pixels[16 * 32 + 16];
}

void showsTheCube(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    vct::ClipmapDesc desc = testClipmapDesc(2);
    VoxelizeHarness h(td, desc);
    Error error;
    REQUIRE(h.clipmap().update(glm::vec3(16.5f), &error));
    const glm::vec3 radiance(1.0f, 0.5f, 0.25f);
    vct::VoxelMaterial thin;
    thin.thickness = 0.0f;
    h.draw(boxTriangles(glm::vec3(4.5f), glm::vec3(12.5f)), thin, &radiance);
    h.clipmap().finishVoxelization();
    rhi::TextureDesc td32;
    td32.width = td32.height = 32;
    td32.format = rhi::Format::RGBA8_UNORM;
    td32.usage = rhi::TextureUsage::Storage;
    td32.debugName = "debug view";
    const rhi::TextureHandle output = td.device->createTexture(td32);
    REQUIRE(output);
    vct::DebugViewDesc d;
    d.cameraPosition = glm::vec3(8.6f, 8.4f, 30.0f);
    d.view = glm::lookAtRH(d.cameraPosition, glm::vec3(8.6f, 8.4f, 0.0f), glm::vec3(0, 1, 0));
    d.projection = glm::perspectiveRH_ZO(glm::radians(30.0f), 1.0f, 0.1f, 100.0f);
    d.projection[1][1] = -d.projection[1][1];
    d.mode = vct::DebugMode::Opacity;
    glm::u8vec4 p = centrePixel(td, h.clipmap(), d, output);
    CHECK(int(p.r) == 0);  // the +Z face blocks only along z
    CHECK(int(p.g) == 0);
    CHECK(int(p.b) == 255);
    d.mode = vct::DebugMode::Emittance;  // radiance 1, 0.5, 0.25 → Reinhard, then the 1/2.2 power
    p = centrePixel(td, h.clipmap(), d, output);
    CHECK(std::abs(int(p.r) - 186) <= 3);
    CHECK(std::abs(int(p.g) - 155) <= 3);
    CHECK(std::abs(int(p.b) - 123) <= 3);
    d.direction = 0;  // the +X face sends nothing from there
    p = centrePixel(td, h.clipmap(), d, output);
    CHECK(int(p.r) + int(p.g) + int(p.b) == 0);
    d.direction = -1;
    d.mode = vct::DebugMode::Level;
    p = centrePixel(td, h.clipmap(), d, output);
    CHECK(std::abs(int(p.r) - 230) <= 2);  // level 0: red
    d.level = 1;  // the same cube, downsampled into level 1
    p = centrePixel(td, h.clipmap(), d, output);
    CHECK(std::abs(int(p.r) - 230) <= 2);
    CHECK(std::abs(int(p.g) - 153) <= 2);  // level 1: orange
    d.level = -1;
    d.mode = vct::DebugMode::Rewritten;
    p = centrePixel(td, h.clipmap(), d, output);
    CHECK(int(p.r) > 200);  // the first update rewrites everything
    REQUIRE(h.clipmap().update(glm::vec3(16.5f), &error));  // no move: nothing rewritten
    p = centrePixel(td, h.clipmap(), d, output);
    CHECK(int(p.r) == int(p.g));
    // Bad descriptions record nothing.
    d.level = 7;
    CHECK_FALSE(h.clipmap().debugView(d, &error));
    CHECK(error.message.find("level 7") != std::string::npos);
    d.level = -1;
    d.output = {};
    CHECK_FALSE(h.clipmap().debugView(d, &error));
    CHECK(error.message.find("RGBA8_UNORM") != std::string::npos);
    td.device->destroy(output);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("clip-map debug views show the test cube's voxels", "[vct]", showsTheCube)
