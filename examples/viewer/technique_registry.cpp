#include "technique_registry.h"

#include <algorithm>

namespace bricklight::viewer {

namespace {
// A function-local static: registrations run during static initialisation, in any order of files.
std::vector<Technique>& registry() {
    static std::vector<Technique> techniques;
    return techniques;
}
}  // namespace

bool registerTechnique(Technique technique) {
    registry().push_back(std::move(technique));
    return true;
}

std::vector<Technique> registeredTechniques() {
    std::vector<Technique> list = registry();
    std::stable_sort(list.begin(), list.end(), [](const Technique& a, const Technique& b) {
        return a.order != b.order ? a.order < b.order : a.name < b.name;
    });
    return list;
}

}  // namespace bricklight::viewer
