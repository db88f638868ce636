#include "vulkan_errors.h"

namespace bricklight::viewer {

namespace {

const char* resultName(VkResult r) {
    switch (r) {
#define BL_CASE(x) \
    case x: return #x;
        BL_CASE(VK_SUCCESS)
        BL_CASE(VK_NOT_READY)
        BL_CASE(VK_TIMEOUT)
        BL_CASE(VK_SUBOPTIMAL_KHR)
        BL_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        BL_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        BL_CASE(VK_ERROR_INITIALIZATION_FAILED)
        BL_CASE(VK_ERROR_DEVICE_LOST)
        BL_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        BL_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        BL_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        BL_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        BL_CASE(VK_ERROR_SURFACE_LOST_KHR)
        BL_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        BL_CASE(VK_ERROR_OUT_OF_DATE_KHR)
        BL_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
#undef BL_CASE
        default: return "VkResult error";
    }
}

}  // namespace

std::string vkFailed(const char* call, VkResult r) {
    return std::string("vulkan: ") + call + " failed (" + resultName(r) + ")";
}

}  // namespace bricklight::viewer
