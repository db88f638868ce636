// Which resources a shader's declared binding accepts: shared by the validation wrapper and the backends,
// so that a record the wrapper passes is one every backend can bind (and the other way round).
#pragma once

#include <cstdint>
#include <string>

#include "bricklight/rhi.h"

namespace bricklight::rhi {

// Whether a texture of dimension `t`, viewed with `layers` layers (0 = all), can be bound where the shader
// declares `s`: 2D takes one layer of an array or cube; a 2D array takes a 2D, array or cube texture; a
// cube needs all 6 faces of a cube texture.
bool dimensionCompatible(ResourceDimension s, TextureDimension t, uint32_t layers);
// Whether a view of format `f` returns the scalar type `s` the shader's sampler or image declares.
bool scalarCompatible(ResourceScalar s, Format f);

// For messages: "textures[2] (slot 5)", a class in the singular ("read buffer", by class index) and a
// declared dimension's name ("2D array").
const char* bindingClassSingular(unsigned bindingClass);
std::string slotField(BindingClass c, size_t index, uint32_t slot);
const char* dimensionName(ResourceDimension d);

}  // namespace bricklight::rhi
