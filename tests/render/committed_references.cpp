#include "committed_references.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <map>
#include <vector>

namespace bricklight::testing {

namespace {

// Every AOV as three channels "<aov>.R/G/B". The noisy AOVs (combined, direct, indirect diffuse, ao) as half
// floats: their rounding (2^-11 relative) is far below the noise of 512 samples and below every tolerance that
// compares with them, and it halves the files. Albedo, normal and depth stay 32-bit floats: the foliage tests
// threshold the albedo, and depth has no bound a half can hold.
bool storedAsHalf(render::Aov aov) {
    return aov == render::Aov::Combined || aov == render::Aov::Direct || aov == render::Aov::IndirectDiffuse || aov == render::Aov::Ao;
}

constexpr const char* kKeyAttribute = "bricklight:referenceKey";
constexpr const char* kSppAttribute = "bricklight:samplesPerPixel";
constexpr const char* kNameAttribute = "bricklight:recipe";

// key -> path of every committed file, read once per process (the headers only).
const std::map<std::string, std::string>& committedIndex() {
    static const std::map<std::string, std::string> index = [] {
        std::map<std::string, std::string> keys;
        std::error_code ec;
        for (const auto& entry : std::filesystem::directory_iterator(committedReferenceDir(), ec)) {
            if (entry.path().extension() != ".exr") continue;
            const std::string key = committedReferenceKey(entry.path().string());
            if (!key.empty()) keys.emplace(key, entry.path().string());
        }
        return keys;
    }();
    return index;
}

}  // namespace

std::string committedReferenceDir() { return BRICKLIGHT_TEST_COMMITTED_REFERENCE_DIR; }

bool committedReferencesAvailable() { return true; }

std::string committedReferenceKey(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        (void)OIIO::geterror();  // a file we cannot read is no reference: nothing to report
        return "";
    }
    return in->spec().get_string_attribute(kKeyAttribute);
}

bool readCommittedReference(const std::string& key, uint32_t width, uint32_t height, uint32_t spp, AovImages& aovs) {
    const auto found = committedIndex().find(key);
    if (found == committedIndex().end()) return false;
    auto in = OIIO::ImageInput::open(found->second);
    if (!in) {
        (void)OIIO::geterror();
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    constexpr int kChannels = 3 * int(render::Aov::Count);
    if (spec.width != int(width) || spec.height != int(height) || spec.nchannels != kChannels ||
        spec.get_int_attribute(kSppAttribute) != int(spp))
        return false;  // a key collision or a damaged file: traced instead
    std::vector<float> pixels(size_t(width) * height * kChannels);
    if (!in->read_image(0, 0, 0, kChannels, OIIO::TypeDesc::FLOAT, pixels.data())) {
        (void)in->geterror();
        return false;
    }
    // OpenEXR keeps channels sorted by name: each is found by its name, not its place.
    const char* rgb[3] = {"R", "G", "B"};
    for (size_t a = 0; a < aovs.size(); ++a) {
        render::Image& img = aovs[a];
        img.width = width;
        img.height = height;
        img.rgb.resize(size_t(width) * height * 3);
        for (size_t c = 0; c < 3; ++c) {
            const int channel = spec.channelindex(std::string(render::aovName(render::Aov(a))) + "." + rgb[c]);
            if (channel < 0) return false;
            for (size_t p = 0; p < size_t(width) * height; ++p) img.rgb[3 * p + c] = pixels[p * kChannels + size_t(channel)];
        }
    }
    return true;
}

bool writeCommittedReference(const std::string& path, const std::string& key, const std::string& name, uint32_t spp,
                             const AovImages& aovs, std::string* error) {
    const uint32_t width = aovs[0].width, height = aovs[0].height;
    constexpr int kChannels = 3 * int(render::Aov::Count);
    OIIO::ImageSpec spec(int(width), int(height), kChannels, OIIO::TypeDesc::FLOAT);
    spec.channelnames.clear();
    spec.channelformats.clear();
    const char* rgb[3] = {"R", "G", "B"};
    std::vector<float> pixels(size_t(width) * height * kChannels);
    for (size_t a = 0; a < aovs.size(); ++a) {
        if (aovs[a].width != width || aovs[a].height != height) {
            *error = "AOV " + std::string(render::aovName(render::Aov(a))) + " has another size";
            return false;
        }
        for (int c = 0; c < 3; ++c) {
            spec.channelnames.push_back(std::string(render::aovName(render::Aov(a))) + "." + rgb[c]);
            spec.channelformats.push_back(storedAsHalf(render::Aov(a)) ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
        }
        for (size_t p = 0; p < size_t(width) * height; ++p)
            for (size_t c = 0; c < 3; ++c) pixels[p * kChannels + 3 * a + c] = aovs[a].rgb[3 * p + c];
    }
    spec.attribute("compression", "zip");
    spec.attribute(kKeyAttribute, key);
    spec.attribute(kNameAttribute, name);
    spec.attribute(kSppAttribute, int(spp));
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        *error = OIIO::geterror();
        return false;
    }
    bool ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
    ok = out->close() && ok;
    if (!ok) *error = "'" + path + "': " + out->geterror();
    return ok;
}

}  // namespace bricklight::testing
