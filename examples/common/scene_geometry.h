// Scene geometry for the examples, tests and benchmark: built-in procedural scenes (the Cornell box from
// its published measurements, a ~1M-triangle instanced field) and model files through assimp. Plain CPU
// data: meshes with a base colour and emission, placed by instances.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "load_limits.h"

namespace bricklight::scenes {

// A texture a program makes (the built-in scenes' procedural textures) in place of an image file: RGBA8, rows
// top to bottom, the colour sRGB-encoded and the alpha linear (a coverage), as a PNG holds them. Needs no
// image library: builds without OpenImageIO use it too.
struct GeneratedTexture {
    std::string name;  // for messages
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;  // width * height * 4 bytes
};

struct TriangleMesh {
    std::string name;
    std::vector<float> positions;   // xyz per vertex
    std::vector<uint32_t> indices;  // 3 per triangle
    std::vector<float> normals;     // optional: 3 per vertex (shading normals; else the triangles' own)
    std::vector<float> uvs;         // optional: 2 per vertex (texture coordinates, v down the image)
    std::string baseColorTexture;   // optional: an image file; multiplies `albedo` (sRGB-encoded)
    // ...or the encoded bytes of a texture embedded in the model file (PNG, JPEG...), named for messages
    // by baseColorTexture ("file.glb*0.png": the index and the format).
    std::shared_ptr<std::vector<uint8_t>> embeddedTexture;
    // ...or generated texels (not with baseColorTexture): the base colour texture, its alpha the coverage of
    // alpha testing unless `alphaTexture` names an opacity map. Shared by the meshes that use it (one layer).
    std::shared_ptr<const GeneratedTexture> generatedTexture;
    glm::vec3 albedo{0.8f};    // base colour (linear)
    glm::vec3 emission{0.0f};  // emitted radiance (linear, W / (sr m^2) in the scene's units)
    float roughness = 1.0f;
    float metalness = 0.0f;
    // A dielectric specular layer (reflectance 0.04 at normal incidence, GGX with `roughness`), as
    // metallic-roughness materials have; off: plain Lambertian (the measured scenes' materials).
    bool specular = false;
    // Glass: the share of light that a clear dielectric (index of refraction `ior`, GGX microfacets of
    // `roughness`; smooth below 0.02) reflects and refracts instead of the opaque material above: 0 opaque, 1
    // clear glass (no absorption). Glass meshes must be closed and wound counter-clockwise seen from outside:
    // the side a ray meets says whether it enters or leaves. Checked by GpuScene: transmission in [0, 1], ior
    // finite in (1, 3].
    float transmission = 0.0f;
    float ior = 1.5f;
    // Alpha testing (foliage, fences: glTF alphaMode MASK, OBJ map_d): a surface point is there only where its
    // coverage, baseAlpha times the alpha of `alphaTexture` (or, without one, of the base colour texture;
    // 1 without either), is at least `alphaCutoff`. 0: opaque, nothing is tested. The model importer's
    // reply must hold both in [0, 1].
    float alphaCutoff = 0.0f;
    float baseAlpha = 1.0f;
    // Optional: an image file whose alpha is the coverage (OBJ's map_d). An image without an alpha channel
    // (a grey opacity map) gives its first channel instead. Empty: the base colour texture's alpha.
    std::string alphaTexture;
    bool alphaTested() const { return alphaCutoff > 0.0f; }
    uint32_t triangleCount() const { return uint32_t(indices.size() / 3); }
    // Deforming (skinning, cloth): `SceneGeometry::animate` rewrites `positions` (same vertex count and
    // indices); they stay within these local bounds at every frame. Renderers keep such a mesh in a buffer of
    // their own, rewritten each frame, and give it to the distance field as the application's buffers.
    bool deforming = false;
    glm::vec3 deformingBoundsMin{0.0f}, deformingBoundsMax{0.0f};
};

// Light from outside the geometry: a uniform sky and an optional sun (a directional light).
struct Environment {
    glm::vec3 skyRadiance{0.0f};
    glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};  // towards the sun
    glm::vec3 sunIrradiance{0.0f};             // on a surface facing the sun
    float sunAngle = 0.0f;                     // the sun's full angular diameter (radians, 0..0.5): 0 a point sun
};

// A point light (radiant intensity in W/sr, in the scene's units) or, with a cone, a spot light.
struct PointLight {
    glm::vec3 position{0.0f};
    glm::vec3 intensity{0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // spot: the cone's axis
    float innerConeRadians = 3.2f;            // > pi: no cone (a point light)
    float outerConeRadians = 3.2f;
};

struct Camera {
    glm::vec3 eye{0.0f, 0.0f, 5.0f};
    glm::vec3 at{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float verticalFovDegrees = 45.0f;
};

struct MeshInstance {
    uint32_t mesh = 0;
    glm::mat4 transform{1.0f};
    // Moved by `SceneGeometry::animate`: the renderers register it as a dynamic instance of the distance field
    // (rebuilt over the static field every frame, docs/sdf.md *Update model*), not a static one moved.
    bool dynamic = false;
};

struct SceneGeometry {
    std::string name;
    std::vector<TriangleMesh> meshes;
    std::vector<MeshInstance> instances;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // world bounds of all instances
    Environment environment;
    std::vector<PointLight> pointLights;
    Camera camera;                               // the scene's default view
    std::vector<std::string> warnings;           // what loading skipped (e.g. embedded textures)
    LoadLimits loadLimits;                       // what it was loaded under: its textures are read under the same
    // Animated scenes: moves instances (and lights, which are emissive instances) to `frame`.
    std::function<void(SceneGeometry&, uint32_t frame)> animate;
    uint64_t triangleCount() const;              // over instances
    void computeBounds();
};

// Cornell's published box, in millimetres (about 556 x 548.8 x 559.2; open at z = 0).
SceneGeometry cornellBox();
// About `targetTriangles` triangles: a tessellated ground and rows of instanced spheres and tori.
SceneGeometry proceduralField(uint32_t targetTriangles);
// Appends a closed axis-aligned box [lo, hi] to `m`, counter-clockwise seen from outside.
void addBox(TriangleMesh& m, glm::vec3 lo, glm::vec3 hi);
// Appends the quad a, b, c, d (two triangles; facing the side from which a → b → c runs counter-clockwise).
void addQuad(TriangleMesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d);
// A unit icosphere (radius 1) with 20 * 4^subdivisions triangles, wound counter-clockwise seen from outside.
TriangleMesh icosphere(uint32_t subdivisions);
// A torus of about `triangles` triangles (the benchmark's moving dynamic object).
TriangleMesh torus(float majorRadius, float minorRadius, uint32_t triangles);
// OBJ, glTF, PLY, FBX... through assimp, node transforms applied. Empty scene and `error` set on failure
// ("cannot load 'path': why"). The file and what it references must be regular files within `limits`;
// the import runs in a child process with a time and memory limit where the platform allows
// (isolated_call.h; LoadLimits::isolateImport), so that a file assimp crashes or hangs on is an error.
SceneGeometry loadModel(const std::string& path, std::string* error, const LoadLimits& limits = {});
// Two rooms sharing a wall `wallThickness` thick (metres); the sun enters the first through a roof
// opening; the camera looks at the shared wall from the second, closed room: all light there is leakage.
SceneGeometry twoRooms(float wallThickness);
// A colonnade courtyard (pillars, arches, a gallery roof, a thin hanging cloth, open to the sky) under sun and sky.
SceneGeometry atrium();
// A closed room with a torus that moves and a small ceiling light that travels over a scripted path.
// What the `dynamic` room holds besides the room: a moving torus and a moving ceiling light (always), a
// crowd of rigid movers, a deforming mesh.
struct DynamicRoomContent {
    bool crowd = true;
    bool deforming = true;
};
SceneGeometry dynamicRoom(DynamicRoomContent content = {});
// The Cornell box with a glass sphere (ior 1.5, roughness 0.1, 1280 triangles) in place of the short block, in
// front of the tall one: the renderer's example of a custom material that traces cones (docs/vct.md).
SceneGeometry cornellGlass();
// The Cornell box with a metal floor (albedo 0.9, metalness 1) of the given perceptual roughness: mirror-like at
// 0.05 (the default of "cornell-mirror"), glossy at 0.3.
SceneGeometry cornellMirror(float roughness);
// A meadow of grass tufts (crossed alpha-tested cards), a tree and a hedge of leaf cards before an opaque wall,
// under sun and sky; its grass and leaf textures are generated (GeneratedTexture), alpha cut-off 0.5.
SceneGeometry foliage();
// An L-shaped corridor of single-sided walls lit by one lamp around the corner from the camera (corridor_scene.cpp).
SceneGeometry corridor();
// The built-in scenes' names, for messages.
const char* builtinSceneNames();
// A built-in scene by name ("cornell", "cornell-glass", "cornell-mirror[:ROUGHNESS]", "two-rooms[:THICKNESS]", "atrium", "dynamic", "field",
// "foliage", "corridor"), or a model
// file (loadModel, under `limits`).
SceneGeometry loadScene(const std::string& nameOrPath, std::string* error, const LoadLimits& limits = {});

}  // namespace bricklight::scenes
