// Voxel cone tracing's energy in closed form: the closed emitting sphere of tests/gi/gi_energy_tests.cpp (albedo
// rho, every surface emitting radiance 1 towards the inside), seen through the renderer's fast path with
// `--gi vxgi`. Every point receives the same light, so the indirect-diffuse output is known exactly: rho after one
// bounce, rho / (1 - rho) after all of them. One bounce measures the cones' gather from the clip-map; every bounce
// also what the voxelization's own cones (blVoxelIndirect) pass on per bounce.
#include <cmath>

#include "backend_test.h"
#include "raster_renderer.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kSize = 32;
constexpr float kRho = 0.5f;

double sphereIndirect(TestDevice& td, bool bounces, uint32_t frameCount) {
    render::RasterOptions o;
    o.width = o.height = kSize;
    o.gi = true;
    o.giTechnique = render::GiTechnique::Vct;
    o.giFeedback = bounces;
    // Its emitters are lights of the renderer's voxel emittance: 320 triangles (2 subdivisions) keep a frame short.
    return indirectMeanAfter(td, emittingSphere(kRho, 1.0f, 2), o, frameCount);
}

// Measured (lavapipe and llvmpipe alike, 32², 320 triangles): one bounce 0.415 (83 %), every bounce after 16 frames
// 0.671 (67 %; not yet converged: the temporal blend takes tens of frames, and a closed box along the axes goes from
// 85 % at 16 frames to 89.5 % at 96, its bounce cones passing about 0.94 a bounce). Before a tilted surface's
// voxels sent the light their opacity takes (resolve_light.comp, voxelize.glsl): 0.318 (64 %) and 0.455. An
// axis-aligned closed box gathers 95 % in one bounce (89 % before), the same box turned 30° and 20° 81 % (69 %): what
// is left on tilted surfaces is the six directions' (a cone reads a tilted wall's other side on the axes whose
// component disagrees with its own; docs/vct.md, *Energy*). Bounds: one bounce within 25 %, every bounce within 42 %
// (the earlier 64 % and 45 % fail them), and neither above the closed form by more than 5 %.
void closedSphereEnergy(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const double one = sphereIndirect(td, false, 4);
    const double every = sphereIndirect(td, true, 16);
    WARN(backend << ": VCT, closed emitting sphere, albedo " << kRho << ": one bounce " << one << " (closed form " << kRho
                 << "), every bounce " << every << " (closed form " << kRho / (1.0f - kRho) << ")");
    CHECK(one / kRho > 0.75);
    CHECK(one / kRho < 1.05);
    CHECK(every / (kRho / (1.0 - kRho)) > 0.58);
    CHECK(every / (kRho / (1.0 - kRho)) < 1.05);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("voxel cone tracing in a closed emitting sphere gives the closed form's light, one bounce and every bounce",
             "[vct]", closedSphereEnergy)
