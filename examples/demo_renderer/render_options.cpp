#include "render_options.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace bricklight::render {

namespace {

bool number(const char* text, const std::string& option, uint32_t lo, uint32_t hi, uint32_t* out, std::string* error) {
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::isdigit(static_cast<unsigned char>(text[0])) ? std::strtoull(text, &end, 10) : 0;
    if (!end || *end || errno == ERANGE || v < lo || v > hi) {
        *error = option + " expects a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) + " (got '" + text + "')";
        return false;
    }
    *out = uint32_t(v);
    return true;
}

// A limit in 1..2^62, digits only.
bool bigNumber(const char* text, const std::string& option, uint64_t* out, std::string* error) {
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::isdigit(static_cast<unsigned char>(text[0])) ? std::strtoull(text, &end, 10) : 0;
    if (!v || !end || *end || errno == ERANGE || v > (1ull << 62)) {
        *error = option + " expects a whole number in 1..2^62 (got '" + text + "')";
        return false;
    }
    *out = v;
    return true;
}

}  // namespace

bool parseWholeNumber(const char* text, const std::string& option, uint32_t lo, uint32_t hi, uint32_t* out,
                      std::string* error) {
    return number(text, option, lo, hi, out, error);
}

OptionParse parseSharedOption(int argc, char** argv, int& i, RenderOptions& o, std::string* error) {
    const std::string a = argv[i];
    const char* v = nullptr;
    auto value = [&] {
        if (i + 1 >= argc) {
            *error = a + " needs a value";
            return false;
        }
        v = argv[++i];
        return true;
    };
    auto done = [](bool ok) { return ok ? OptionParse::Consumed : OptionParse::Error; };
    auto whole = [&](uint32_t lo, uint32_t hi, uint32_t* out) { return done(value() && number(v, a, lo, hi, out, error)); };
    auto big = [&](uint64_t* out) { return done(value() && bigNumber(v, a, out, error)); };
    if (a == "--scene") {
        if (!value()) return OptionParse::Error;
        o.scene = v;
        return OptionParse::Consumed;
    }
    if (a == "--backend") {
        if (!value()) return OptionParse::Error;
        o.backend = v;
        return OptionParse::Consumed;
    }
    if (a == "--width") return whole(1, 8192, &o.width);
    if (a == "--height") return whole(1, 8192, &o.height);
    if (a == "--frames") {
        o.framesGiven = true;
        return whole(1, 100000, &o.frames);
    }
    if (a == "--gi") {
        if (!value()) return OptionParse::Error;
        const std::string s = v;
        if (s != "sdf" && s != "vxgi" && s != "none") {
            *error = "--gi must be sdf, vxgi or none (got '" + s + "')";
            return OptionParse::Error;
        }
        o.gi = s != "none";
        o.giTechnique = s == "vxgi" ? GiTechnique::Vct : GiTechnique::Sdf;
        return OptionParse::Consumed;
    }
    if (a == "--ao") {
        if (!value()) return OptionParse::Error;
        const std::string s = v;
        if (s != "vxao" && s != "none") {
            *error = "--ao must be vxao or none (got '" + s + "')";
            return OptionParse::Error;
        }
        o.vxao = s == "vxao";
        return OptionParse::Consumed;
    }
    if (a == "--gi-unseen") {
        if (!value()) return OptionParse::Error;
        const std::string s = v;
        if (s != "vxgi" && s != "path" && s != "none") {
            *error = "--gi-unseen must be vxgi, path or none (got '" + s + "')";
            return OptionParse::Error;
        }
        o.giUnseenFromVct = s == "vxgi";
        o.giUnseenPath = s == "path";
        return OptionParse::Consumed;
    }
    if (a == "--vct-occlusion") {
        if (!value()) return OptionParse::Error;
        const std::string s = v;
        if (s != "voxels" && s != "sdf") {
            *error = "--vct-occlusion must be voxels or sdf (got '" + s + "')";
            return OptionParse::Error;
        }
        o.vctSdfOcclusion = s == "sdf";
        return OptionParse::Consumed;
    }
    if (a == "--shadows") {
        if (!value()) return OptionParse::Error;
        const std::string s = v;
        if (s != "bvh" && s != "shadowmap" && s != "hybrid") {
            *error = "--shadows must be bvh, shadowmap or hybrid (got '" + s + "')";
            return OptionParse::Error;
        }
        o.shadows = s == "shadowmap" ? ShadowMode::ShadowMap : s == "hybrid" ? ShadowMode::Hybrid : ShadowMode::Bvh;
        return OptionParse::Consumed;
    }
    if (a == "--reflections") {
        if (!value()) return OptionParse::Error;
        const std::string s = v;
        if (s != "gi" && s != "hybrid") {
            *error = "--reflections must be gi or hybrid (got '" + s + "')";
            return OptionParse::Error;
        }
        o.reflections = s == "hybrid" ? ReflectionMode::Hybrid : ReflectionMode::Gi;
        return OptionParse::Consumed;
    }
    if (a == "--foliage") {
        if (!value()) return OptionParse::Error;
        const std::string s = v;
        if (s != "alpha-aware" && s != "opaque" && s != "left-out") {
            *error = "--foliage must be alpha-aware, opaque or left-out (got '" + s + "')";
            return OptionParse::Error;
        }
        o.foliage = s == "opaque" ? FoliageMode::Opaque : s == "left-out" ? FoliageMode::LeftOut : FoliageMode::AlphaAware;
        return OptionParse::Consumed;
    }
    if (a == "--shadow-resolution") return whole(kMinShadowResolution, kMaxShadowResolution, &o.sunShadows.resolution);
    if (a == "--shadow-pcf") return whole(0, kMaxShadowPcfRadius, &o.sunShadows.pcfRadius);
    if (a == "--vct-voxel") {
        if (!value()) return OptionParse::Error;
        char* end = nullptr;
        const float size = std::strtof(v, &end);
        if (!*v || *end || !(size > 0.0f && size < 1.0e6f)) {
            *error = "--vct-voxel expects the finest voxel's size in scene units, above 0 (got '" + std::string(v) + "')";
            return OptionParse::Error;
        }
        o.vctVoxel = size;
        return OptionParse::Consumed;
    }
    if (a == "--sun-angle") {
        if (!value()) return OptionParse::Error;
        char* end = nullptr;
        const float degrees = std::strtof(v, &end);
        if (!*v || *end || !(degrees >= 0.0f && degrees < 28.0f)) {
            *error = "--sun-angle expects degrees in 0..28 (got '" + std::string(v) + "')";
            return OptionParse::Error;
        }
        o.sunAngleDegrees = degrees;
        return OptionParse::Consumed;
    }
    if (a == "--shadow-lambda") {
        if (!value()) return OptionParse::Error;
        char* end = nullptr;
        const float lambda = std::strtof(v, &end);
        if (!*v || *end || !(lambda >= 0.0f && lambda <= 1.0f)) {
            *error = "--shadow-lambda expects a number in 0..1 (got '" + std::string(v) + "')";
            return OptionParse::Error;
        }
        o.sunShadows.splitLambda = lambda;
        return OptionParse::Consumed;
    }
    if (a == "--gi-scale") {
        uint32_t s = 0;
        if (whole(25, 100, &s) == OptionParse::Error) return OptionParse::Error;
        using R = gi::InternalResolution;
        if (s == 100) o.giScale = R::Native;
        else if (s == 75) o.giScale = R::Percent75;
        else if (s == 50) o.giScale = R::Percent50;
        else if (s == 25) o.giScale = R::Percent25;
        else {
            *error = "--gi-scale must be 100, 75, 50 or 25";
            return OptionParse::Error;
        }
        return OptionParse::Consumed;
    }
    if (a == "--single-bounce") {
        o.singleBounce = true;
        return OptionParse::Consumed;
    }
    if (a == "--validate") {
        o.validate = true;
        return OptionParse::Consumed;
    }
    if (a == "--exposure") {
        if (!value()) return OptionParse::Error;
        char* end = nullptr;
        o.exposure = std::strtof(v, &end);
        if (!*v || *end || !(o.exposure > 0.0f) || !std::isfinite(o.exposure)) {
            *error = "--exposure expects a positive number";
            return OptionParse::Error;
        }
        return OptionParse::Consumed;
    }
    if (a == "--camera") {
        if (!value()) return OptionParse::Error;
        char* end = nullptr;
        const char* at = v;
        for (int k = 0; k < 6; ++k) {
            o.camera[k] = std::strtof(at, &end);
            if (end == at || !std::isfinite(o.camera[k]) || (k < 5 && *end != ',') || (k == 5 && *end)) {
                *error = "--camera expects six numbers: EYE_X,EYE_Y,EYE_Z,AT_X,AT_Y,AT_Z (got '" + std::string(v) + "')";
                return OptionParse::Error;
            }
            at = end + 1;
        }
        o.haveCamera = true;
        return OptionParse::Consumed;
    }
    // Limits on model and texture files (examples/common/load_limits.h).
    scenes::LoadLimits& l = o.limits;
    if (a == "--max-file-bytes") return big(&l.maxFileBytes);
    if (a == "--max-json-bytes") return big(&l.maxJsonBytes);
    if (a == "--max-json-depth") return whole(1, 1u << 20, &l.maxJsonDepth);
    if (a == "--max-vertices") return big(&l.maxVertices);
    if (a == "--max-indices") return big(&l.maxIndices);
    if (a == "--max-face-indices") return whole(3, 1u << 20, &l.maxFaceIndices);
    if (a == "--max-nodes") return big(&l.maxNodes);
    if (a == "--max-node-depth") return whole(1, 1u << 20, &l.maxNodeDepth);
    if (a == "--max-texture-pixels") return big(&l.maxTexturePixels);
    if (a == "--allow-outside-paths") {
        l.allowOutsidePaths = true;
        return OptionParse::Consumed;
    }
    if (a == "--import-timeout") {
        uint32_t seconds = 0;
        const OptionParse r = whole(1, 86400, &seconds);
        if (r == OptionParse::Consumed) l.importTimeoutSeconds = seconds;
        return r;
    }
    if (a == "--import-memory") return big(&l.importMemoryBytes);
    return OptionParse::NotShared;
}

bool checkSharedOptions(const RenderOptions& o, std::string* error) {
    if (o.backend != "vulkan" && o.backend != "gl") {
        *error = "--backend must be vulkan or gl (got '" + o.backend + "')";
        return false;
    }
    if (o.reflections == ReflectionMode::Hybrid && !(o.gi && o.giTechnique == GiTechnique::Sdf)) {
        *error = "--reflections hybrid needs --gi sdf: its rays read the SDF GI's radiance cache";
        return false;
    }
    return true;
}

const char* sharedOptionsUsage() {
    return "  [--scene NAME|FILE] [--backend vulkan|gl] [--width W] [--height H] [--frames N]\n"
           "  [--camera EX,EY,EZ,AX,AY,AZ] [--exposure E] [--gi sdf|vxgi|none] [--ao vxao|none]\n"
           "  [--gi-scale 100|75|50|25] [--vct-occlusion voxels|sdf] [--vct-voxel SIZE] [--gi-unseen vxgi|path|none]\n"
           "  [--shadows bvh|shadowmap|hybrid] [--shadow-resolution 64..4096] [--shadow-lambda 0..1] [--shadow-pcf 0..3]\n"
           "  [--sun-angle DEGREES]\n"
           "  [--reflections gi|hybrid] [--foliage alpha-aware|opaque|left-out] [--single-bounce] [--validate]\n"
           "  [--max-file-bytes N] [--max-json-bytes N] [--max-json-depth N] [--max-vertices N] [--max-indices N]\n"
           "  [--max-face-indices N] [--max-nodes N] [--max-node-depth N] [--max-texture-pixels N]\n"
           "  [--allow-outside-paths] [--import-timeout SECONDS] [--import-memory BYTES]\n";
}

scenes::SceneGeometry loadSceneOf(const RenderOptions& o, std::string* error) {
    scenes::SceneGeometry scene = scenes::loadScene(o.scene, error, o.limits);
    if (scene.meshes.empty()) {
        if (error->empty()) *error = "the scene is empty";
        return scene;
    }
    if (o.haveCamera) {
        scene.camera.eye = glm::vec3(o.camera[0], o.camera[1], o.camera[2]);
        scene.camera.at = glm::vec3(o.camera[3], o.camera[4], o.camera[5]);
    }
    if (o.sunAngleDegrees >= 0.0f) scene.environment.sunAngle = glm::radians(o.sunAngleDegrees);
    return scene;
}

RasterOptions rasterOptionsOf(const RenderOptions& o) {
    RasterOptions ro;
    ro.width = o.width;
    ro.height = o.height;
    ro.gi = o.gi;
    ro.giTechnique = o.giTechnique;
    ro.vxao = o.vxao;
    ro.vctSdfOcclusion = o.vctSdfOcclusion;
    ro.giUnseenFromVct = o.giUnseenFromVct;
    ro.giUnseenPath = o.giUnseenPath;
    ro.vctFinestVoxel = o.vctVoxel;
    ro.giResolution = o.giScale;
    ro.giFeedback = !o.singleBounce;
    ro.shadows = o.shadows;
    ro.sunShadows = o.sunShadows;
    ro.reflections = o.reflections;
    ro.foliage = o.foliage;
    return ro;
}

uint32_t framesToRender(const RenderOptions& o, const scenes::SceneGeometry& scene) {
    return o.gi && !o.framesGiven && !scene.animate ? kDefaultGiFrames : o.frames;
}

bool animateTo(scenes::SceneGeometry& scene, RasterRenderer& renderer, uint32_t frame, std::string* error) {
    if (frame == 0 || !scene.animate) return true;
    scene.animate(scene, frame);
    std::string why;
    if (renderer.setScene(scene, &why)) return true;
    *error = "frame " + std::to_string(frame) + ": " + why;
    return false;
}

}  // namespace bricklight::render
