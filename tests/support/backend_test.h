// One test body, both backends: BACKEND_TEST("name", "[tag]", body) registers "name (vulkan)" tagged
// [tag][vulkan] and "name (gl)" tagged [tag][gl], each calling body(backendName).
#pragma once

#include <catch2/catch.hpp>

#include "test_device.h"

#ifdef BRICKLIGHT_HAS_VULKAN
#define BL_VULKAN_TEST(name, tag, body) \
    TEST_CASE(name " (vulkan)", tag "[vulkan]") { body("vulkan"); }
#else
#define BL_VULKAN_TEST(name, tag, body)
#endif
#ifdef BRICKLIGHT_HAS_GL
#define BL_GL_TEST(name, tag, body) \
    TEST_CASE(name " (gl)", tag "[gl]") { body("gl"); }
#else
#define BL_GL_TEST(name, tag, body)
#endif
#define BACKEND_TEST(name, tag, body) BL_VULKAN_TEST(name, tag, body) BL_GL_TEST(name, tag, body)

// No message from the device (or anything else that reports into its list) during a test.
#define REQUIRE_NO_MESSAGES(testDevice)                                                      \
    do {                                                                                     \
        for (const std::string& m : *(testDevice).messages) UNSCOPED_INFO("message: " << m); \
        REQUIRE((testDevice).messages->empty());                                             \
    } while (0)
