#include "generated_texture.h"

#include <algorithm>
#include <cmath>

namespace bricklight::render {

bool generatedTextureLayer(const scenes::GeneratedTexture& texture, uint32_t size, std::vector<uint8_t>* texels, std::string* error) {
    const uint32_t w = texture.width, h = texture.height;
    if (w == 0 || h == 0 || w > 16384 || h > 16384 || texture.rgba.size() != size_t(w) * h * 4) {
        if (error)
            *error = "generated texture '" + texture.name + "' is " + std::to_string(w) + " x " + std::to_string(h) + " with " +
                     std::to_string(texture.rgba.size()) + " bytes (1..16384 a side and 4 bytes a texel expected)";
        return false;
    }
    const size_t offset = texels->size();
    texels->resize(offset + size_t(size) * size * 4);
    uint8_t* out = texels->data() + offset;
    if (w == size && h == size) {
        std::copy(texture.rgba.begin(), texture.rgba.end(), out);
        return true;
    }
    // Texel centres onto texel centres: x_source = (x + 0.5) * w / size - 0.5.
    auto at = [&](uint32_t x, uint32_t y, int c) { return float(texture.rgba[(size_t(y) * w + x) * 4 + size_t(c)]); };
    for (uint32_t y = 0; y < size; ++y) {
        const float sy = std::clamp((float(y) + 0.5f) * float(h) / float(size) - 0.5f, 0.0f, float(h - 1));
        const uint32_t y0 = uint32_t(sy), y1 = std::min(y0 + 1, h - 1);
        const float fy = sy - float(y0);
        for (uint32_t x = 0; x < size; ++x) {
            const float sx = std::clamp((float(x) + 0.5f) * float(w) / float(size) - 0.5f, 0.0f, float(w - 1));
            const uint32_t x0 = uint32_t(sx), x1 = std::min(x0 + 1, w - 1);
            const float fx = sx - float(x0);
            for (int c = 0; c < 4; ++c) {
                const float top = at(x0, y0, c) + (at(x1, y0, c) - at(x0, y0, c)) * fx;
                const float bottom = at(x0, y1, c) + (at(x1, y1, c) - at(x0, y1, c)) * fx;
                out[(size_t(y) * size + x) * 4 + size_t(c)] = uint8_t(std::lround(top + (bottom - top) * fy));
            }
        }
    }
    return true;
}

}  // namespace bricklight::render
