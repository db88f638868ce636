// assimp's C API, loaded when a model file is first opened: programs that only use built-in scenes (the
// benchmark copied to a bare GPU machine) need no assimp at run time.
#pragma once

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/material.h>

#include <string>

namespace bricklight::scenes {

struct AssimpApi {
    decltype(&aiImportFileEx) importFileEx = nullptr;
    decltype(&aiReleaseImport) releaseImport = nullptr;
    decltype(&aiGetErrorString) errorString = nullptr;
    decltype(&aiGetMaterialColor) materialColor = nullptr;
    decltype(&aiGetMaterialTexture) materialTexture = nullptr;
    decltype(&aiGetMaterialFloatArray) materialFloats = nullptr;
    decltype(&aiGetMaterialString) materialString = nullptr;
    std::string loadError;  // empty: all of the above are there
};

// Loaded once (thread-safe); call it before fork() so that a child never runs the dynamic loader.
const AssimpApi& assimp();

}  // namespace bricklight::scenes
