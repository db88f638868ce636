// Runs on the null device: the check is about building and linking (the parent's shader and ours are
// registered, a scene is created), not about pixels.
#include <cstdio>

#include "bricklight/rhi_validation.h"
#include "bricklight/sdf.h"
#include "bricklight/version.h"

using namespace bricklight;

int main() {
    std::unique_ptr<rhi::IDevice> device = rhi::createNullDevice();
    sdf::SceneDesc desc;
    desc.finestVoxelSize = 0.1f;
    desc.atlasBricksPerAxis = 8;
    Error error;
    std::unique_ptr<sdf::SdfScene> scene = sdf::SdfScene::create(*device, desc, &error);
    const bool ownShader = rhi::findShader("field_probe.comp") != nullptr;
    const bool ok = scene && ownShader;
    std::printf("subdirectory_check (Bricklight %s): scene %s, the parent's shader %s: %s\n", BRICKLIGHT_VERSION_STRING,
                scene ? "created" : error.message.c_str(), ownShader ? "registered" : "missing", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
