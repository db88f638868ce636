#include "assimp_api.h"

#include <dlfcn.h>

namespace bricklight::scenes {

namespace {

AssimpApi loadAssimp() {
    AssimpApi api;
    void* lib = nullptr;
    for (const char* name : {"libassimp.so.5", "libassimp.so"})
        if ((lib = dlopen(name, RTLD_NOW | RTLD_LOCAL))) break;
    if (!lib) {
        api.loadError = "assimp (libassimp.so.5) is not installed: only the built-in scenes are available";
        return api;
    }
    api.importFileEx = reinterpret_cast<decltype(api.importFileEx)>(dlsym(lib, "aiImportFileEx"));
    api.releaseImport = reinterpret_cast<decltype(api.releaseImport)>(dlsym(lib, "aiReleaseImport"));
    api.errorString = reinterpret_cast<decltype(api.errorString)>(dlsym(lib, "aiGetErrorString"));
    api.materialColor = reinterpret_cast<decltype(api.materialColor)>(dlsym(lib, "aiGetMaterialColor"));
    api.materialTexture = reinterpret_cast<decltype(api.materialTexture)>(dlsym(lib, "aiGetMaterialTexture"));
    api.materialFloats = reinterpret_cast<decltype(api.materialFloats)>(dlsym(lib, "aiGetMaterialFloatArray"));
    api.materialString = reinterpret_cast<decltype(api.materialString)>(dlsym(lib, "aiGetMaterialString"));
    if (!api.importFileEx || !api.releaseImport || !api.errorString || !api.materialColor || !api.materialTexture || !api.materialFloats ||
        !api.materialString)
        api.loadError = "libassimp lacks its C API";
    return api;
}

}  // namespace

const AssimpApi& assimp() {
    static const AssimpApi api = loadAssimp();
    return api;
}

}  // namespace bricklight::scenes
