// Comparing two backends' outputs of one case, each output with its own tolerance.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

#include "bricklight/conformance.h"

namespace bricklight::conformance {

std::vector<std::string> compareOutputs(const CaseResult& a, const CaseResult& b) {
    std::vector<std::string> diffs;
    if (a.outputs.size() != b.outputs.size()) {
        diffs.push_back("different number of outputs: " + std::to_string(a.outputs.size()) + " vs " +
                        std::to_string(b.outputs.size()));
        return diffs;
    }
    for (size_t i = 0; i < a.outputs.size(); ++i) {
        const Output& x = a.outputs[i];
        const Output& y = b.outputs[i];
        if (x.name != y.name || x.bytes.size() != y.bytes.size()) {
            diffs.push_back("output " + x.name + ": size or name differs");
            continue;
        }
        size_t bad = 0, first = SIZE_MAX;
        double worst = 0.0;
        switch (x.tolerance.kind) {
            case Tolerance::Kind::Exact:
                for (size_t k = 0; k < x.bytes.size(); ++k)
                    if (x.bytes[k] != y.bytes[k]) ++bad, first = std::min(first, k);
                break;
            case Tolerance::Kind::Unorm8:
                for (size_t k = 0; k < x.bytes.size(); ++k) {
                    double d = std::abs(int(x.bytes[k]) - int(y.bytes[k]));
                    worst = std::max(worst, d);
                    if (d > x.tolerance.absolute) ++bad, first = std::min(first, k);
                }
                break;
            case Tolerance::Kind::Float32:
                for (size_t k = 0; k + 4 <= x.bytes.size(); k += 4) {
                    float fa, fb;
                    std::memcpy(&fa, &x.bytes[k], 4);
                    std::memcpy(&fb, &y.bytes[k], 4);
                    double d = std::isnan(fa) != std::isnan(fb) ? INFINITY : std::abs(double(fa) - fb);
                    if (std::isnan(fa) && std::isnan(fb)) d = 0;
                    worst = std::max(worst, d);
                    if (d > x.tolerance.absolute) ++bad, first = std::min(first, k);
                }
                break;
        }
        if (bad) {
            std::ostringstream m;
            m << "output " << x.name << ": " << bad << " element(s) differ beyond tolerance " << x.tolerance.absolute
              << " (first at byte " << first << ", largest difference " << worst << ")";
            diffs.push_back(m.str());
        }
    }
    return diffs;
}

}  // namespace bricklight::conformance
