// The techniques the viewer lists (SDF GI today; voxel cone tracing and the shadow and reflection
// classifiers later). A technique registers itself from its own source file with
// BRICKLIGHT_VIEWER_TECHNIQUE: its panel appears in the viewer without any change to the UI code.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace bricklight::viewer {

class ViewerApp;

struct Technique {
    std::string name;         // the panel's header
    std::string description;  // one line under it
    int order = 100;          // lower first
    // Draws the technique's ImGui widgets; changes go to the app (ViewerApp's settings and requests).
    std::function<void(ViewerApp&)> panel;
};

// Adds a technique; returns true so that it can initialise a static (see the macro).
bool registerTechnique(Technique technique);
// Every registered technique, by `order` then name.
std::vector<Technique> registeredTechniques();

}  // namespace bricklight::viewer

#define BRICKLIGHT_VIEWER_CONCAT2(a, b) a##b
#define BRICKLIGHT_VIEWER_CONCAT(a, b) BRICKLIGHT_VIEWER_CONCAT2(a, b)
// At namespace scope in the technique's .cpp (which must be linked into the viewer executable itself, not
// through a static library, or the linker drops the registration): BRICKLIGHT_VIEWER_TECHNIQUE(technique);
#define BRICKLIGHT_VIEWER_TECHNIQUE(...) \
    static const bool BRICKLIGHT_VIEWER_CONCAT(registeredTechnique, __LINE__) = ::bricklight::viewer::registerTechnique(__VA_ARGS__)
