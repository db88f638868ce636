// Generated textures as texture-array layers (generated_texture.cpp): no image library, so builds without
// OpenImageIO (the benchmark's) resample them the same way.
#include <catch2/catch.hpp>

#include <cmath>

#include "generated_texture.h"

using namespace bricklight;

TEST_CASE("generated textures: copied at the layer size, resampled bilinearly otherwise, malformed ones refused", "[cpu]") {
    scenes::GeneratedTexture t;
    t.name = "ramp";
    t.width = 2;
    t.height = 1;
    t.rgba = {0, 0, 0, 0, 200, 100, 50, 255};  // black transparent | colour opaque
    std::vector<uint8_t> texels(3, 7);         // appended after what is there
    std::string error;
    REQUIRE(render::generatedTextureLayer(t, 4, &texels, &error));
    REQUIRE(texels.size() == 3 + 4 * 4 * 4);
    // Texel centres 0.125 .. 0.875 of the width onto the source's 0.25 and 0.75: clamped, a quarter, three
    // quarters, clamped; every row alike.
    const float weight[4] = {0.0f, 0.25f, 0.75f, 1.0f};
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            INFO(x << "," << y);
            const uint8_t* p = texels.data() + 3 + (y * 4 + x) * 4;
            CHECK(p[0] == uint8_t(std::lround(200 * weight[x])));
            CHECK(p[3] == uint8_t(std::lround(255 * weight[x])));
        }
    // At the layer size: the bytes as they are.
    scenes::GeneratedTexture square = t;
    square.height = 2;
    square.rgba.insert(square.rgba.end(), {1, 2, 3, 4, 5, 6, 7, 8});
    std::vector<uint8_t> copy;
    REQUIRE(render::generatedTextureLayer(square, 2, &copy, &error));
    CHECK(copy == square.rgba);
    // A byte count that does not match the size, or no texels: refused, naming the texture.
    square.rgba.pop_back();
    CHECK(!render::generatedTextureLayer(square, 2, &copy, &error));
    CHECK(error == "generated texture 'ramp' is 2 x 2 with 15 bytes (1..16384 a side and 4 bytes a texel expected)");
    square.width = 0;
    square.rgba.clear();
    CHECK(!render::generatedTextureLayer(square, 2, &copy, &error));
    CHECK(copy.size() == 16);  // nothing appended on failure
}
