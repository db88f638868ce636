// One test body, both backends: SDF_BACKEND_TEST("name", body) registers "name (vulkan)" tagged
// [sdf][vulkan] and "name (gl)" tagged [sdf][gl], each calling body(backendName).
#pragma once

#include <catch2/catch.hpp>

#ifdef BRICKLIGHT_HAS_VULKAN
#define SDF_VULKAN_TEST(name, body) \
    TEST_CASE(name " (vulkan)", "[sdf][vulkan]") { body("vulkan"); }
#else
#define SDF_VULKAN_TEST(name, body)
#endif
#ifdef BRICKLIGHT_HAS_GL
#define SDF_GL_TEST(name, body) \
    TEST_CASE(name " (gl)", "[sdf][gl]") { body("gl"); }
#else
#define SDF_GL_TEST(name, body)
#endif
#define SDF_BACKEND_TEST(name, body) SDF_VULKAN_TEST(name, body) SDF_GL_TEST(name, body)

// No message from the device or the builder during a test.
#define REQUIRE_NO_MESSAGES(testDevice)                                                      \
    do {                                                                                     \
        for (const std::string& m : *(testDevice).messages) UNSCOPED_INFO("message: " << m); \
        REQUIRE((testDevice).messages->empty());                                             \
    } while (0)
