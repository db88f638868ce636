#include "display_view.h"

namespace bricklight::render {

namespace {
const char* const kNames[] = {"final", "direct", "indirect-diffuse", "specular-gi", "albedo", "normal", "depth", "motion",
                              "sdf-distance", "sdf-normal", "sdf-iterations", "sdf-brick-id", "sdf-cascade-id", "sdf-uvw",
                              "gi-radiance-cache", "gi-irradiance-cache", "gi-probes", "gi-probe-sh", "gi-disocclusion",
                              "gi-samples", "vct-opacity", "vct-emittance", "vct-level", "vct-rewritten",
                              "vct-cone-samples", "reflections", "reflection-tile-class", "reflection-rays",
                              "reflection-counters"};
static_assert(sizeof(kNames) / sizeof(kNames[0]) == size_t(View::Count), "a name for every view");
}  // namespace

const char* viewName(View view) { return view < View::Count ? kNames[uint32_t(view)] : "unknown"; }

bool viewFromName(const std::string& name, View* out) {
    for (uint32_t v = 0; v < uint32_t(View::Count); ++v)
        if (name == kNames[v]) {
            *out = View(v);
            return true;
        }
    return false;
}

bool viewIsVct(View view) { return view >= View::VctOpacity && view <= View::VctConeSamples; }

bool viewIsReflection(View view) { return view >= View::Reflections && view < View::Count; }

bool viewNeedsGi(View view) { return view == View::IndirectDiffuse || view == View::SpecularGi || view >= View::SdfDistance; }

}  // namespace bricklight::render
