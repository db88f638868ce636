// Image files the renderer writes: an image with an infinite or NaN pixel is refused, naming the count, and
// nothing is written (issue 36: every comparison against such a file would be silently wrong).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>

#include "image_io.h"

using namespace bricklight;

TEST_CASE("image files: an image with a non-finite pixel is refused and nothing is written", "[render]") {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "bricklight_image_io_tests";
    std::filesystem::create_directories(dir);
    render::Image img;
    img.width = 4;
    img.height = 2;
    img.rgb.assign(4 * 2 * 3, 0.5f);
    img.rgb[4] = std::numeric_limits<float>::quiet_NaN();      // pixel 1
    img.rgb[3 * 6 + 2] = std::numeric_limits<float>::infinity();  // pixel 6
    for (const char* name : {"nan.exr", "nan.png"}) {
        const std::string path = (dir / name).string();
        std::filesystem::remove(path);
        std::string error;
        CHECK_FALSE(render::writeImage(path, img, 1.0f, &error));
        INFO(error);
        CHECK(error.find("2 of 8 pixels are infinite or NaN") != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(path));
    }
    img.rgb[4] = 0.5f;
    img.rgb[3 * 6 + 2] = 0.5f;
    std::string error;
    CHECK(render::writeImage((dir / "finite.exr").string(), img, 1.0f, &error));
    std::filesystem::remove_all(dir);
}
