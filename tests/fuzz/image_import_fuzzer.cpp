// libFuzzer target: texture images through the renderer's texture loader (header checks, then
// OpenImageIO's readers, then resampling). An input is
//   byte 0: the format (the name's extension, from kFormats) and, in its next bit, how the bytes arrive:
//           as an embedded texture (in memory, as a GLB's) or as a file beside a model;
//   the rest: the image.
// Traps: an error that does not name the image, or a success that did not append exactly one layer.
// OpenImageIO and its format libraries are not instrumented: a crash or hang in them is a finding we can
// only guard against (the header checks keep sizes within the pixel budget).
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "texture_loader.h"

namespace {

const char* const kFormats[] = {"png", "jpg", "tga", "bmp", "gif", "hdr", "exr", "tif", "psd", "pnm", "dds", "ico", "webp", "sgi", "rla", "pic"};
constexpr size_t kFormatCount = sizeof kFormats / sizeof kFormats[0];
constexpr uint32_t kLayerSize = 16;

const std::string& folder() {
    static const std::string dir = [] {
        std::string pattern = (std::filesystem::temp_directory_path() / "image_import_fuzzer.XXXXXX").string();
        if (!mkdtemp(pattern.data())) std::abort();
        return pattern;
    }();
    return dir;
}

}  // namespace

// OpenImageIO 2.4 leaks an error string (allocated in ImageInput::geterror, called inside the library)
// when a reader fails on a broken image; LeakSanitizer would fail the sanitizer build on that third-party
// leak. Read by LeakSanitizer only (the name is its hook); other builds never call it.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOpenImageIO.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    bricklight::scenes::LoadLimits limits;
    limits.maxTexturePixels = 4u << 20;  // 4 Mpixels: decoding stays well inside -rss_limit_mb
    const size_t format = data[0] % kFormatCount;
    const bool embedded = (data[0] / kFormatCount) % 2 == 1;
    const std::vector<uint8_t> bytes(data + 1, data + size);
    std::string path = folder() + "/texture." + kFormats[format];
    if (!embedded) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    } else {
        path = folder() + "/model.glb*0." + kFormats[format];
    }
    std::vector<uint8_t> texels(3, 0);  // something before: a layer is appended, never written over
    std::string error;
    const bool ok = bricklight::render::loadTextureLayer(path, kLayerSize, &texels, &error, embedded ? &bytes : nullptr, limits);
    if (ok && texels.size() != 3 + size_t(kLayerSize) * kLayerSize * 4) __builtin_trap();
    if (!ok && (texels.size() != 3 || error.rfind("'" + path + "' cannot be loaded: ", 0) != 0)) __builtin_trap();
    return 0;
}
