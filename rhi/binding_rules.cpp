#include "binding_rules.h"

namespace bricklight::rhi {

bool dimensionCompatible(ResourceDimension s, TextureDimension t, uint32_t layers) {
    switch (s) {
        case ResourceDimension::Texture2D:
            return t == TextureDimension::Texture2D || (t != TextureDimension::Texture3D && layers == 1);
        case ResourceDimension::Texture2DArray:
            return t == TextureDimension::Texture2DArray || t == TextureDimension::TextureCube ||
                   t == TextureDimension::Texture2D;
        case ResourceDimension::Texture3D: return t == TextureDimension::Texture3D;
        case ResourceDimension::TextureCube: return t == TextureDimension::TextureCube && layers == 6;
        default: return false;
    }
}

const char* bindingClassSingular(unsigned c) {
    static const char* names[] = {"constants block", "texture", "read buffer", "storage buffer", "storage image"};
    return c < 5 ? names[c] : "binding";
}

std::string slotField(BindingClass c, size_t index, uint32_t slot) {
    return std::string(bindingClassName(c)) + "[" + std::to_string(index) + "] (slot " + std::to_string(slot) + ")";
}

const char* dimensionName(ResourceDimension d) {
    switch (d) {
        case ResourceDimension::Texture2D: return "2D";
        case ResourceDimension::Texture2DArray: return "2D array";
        case ResourceDimension::Texture3D: return "3D";
        case ResourceDimension::TextureCube: return "cube";
        case ResourceDimension::Buffer: return "buffer";
        default: return "none";
    }
}

bool scalarCompatible(ResourceScalar s, Format f) {
    const auto k = formatInfo(f).kind;
    switch (s) {
        case ResourceScalar::Uint: return k == FormatInfo::Kind::Uint;
        case ResourceScalar::Sint: return k == FormatInfo::Kind::Sint;
        case ResourceScalar::Float: return k != FormatInfo::Kind::Uint && k != FormatInfo::Kind::Sint;
        default: return true;
    }
}

}  // namespace bricklight::rhi
