// The GI's alpha cache (gi::ContextFlags::AlphaCache) and the alpha pass that fills it (GiContext::alphaPassState,
// bricklight/alpha_pass.glsl): an alpha-tested card with a striped alpha test of known share, drawn through the
// pass, gives its flagged bricks' cells a mean coverage of that share, in every cascade; the same pass again gives
// the same coverage (no randomness); bad use is refused with named messages.
#include "backend_test.h"
#include "bricklight/gi.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

namespace {

void alphaPassCoverage(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    rhi::IDevice& dev = *td.device;
    REQUIRE(dev.capabilities().geometryShader);  // both reference drivers offer them

    // The card: x in [-1, 1], y in [0.05, 1.45], z = 0.013 (off the voxel boundaries), u across x.
    scenes::SceneGeometry g;
    scenes::TriangleMesh card;
    card.name = "card";
    card.positions = {-1, 0.05f, 0.013f, 1, 0.05f, 0.013f, 1, 1.45f, 0.013f, -1, 1.45f, 0.013f};
    card.indices = {0, 1, 2, 0, 2, 3};
    card.alphaCutoff = 0.5f;
    g.meshes.push_back(card);
    g.instances.push_back({0, glm::mat4(1.0f)});
    g.computeBounds();
    sdf::SceneDesc desc;
    desc.cascadeCount = 3;
    desc.finestVoxelSize = 0.1f;
    desc.atlasBricksPerAxis = 32;
    desc.errorCallback = [&td](rhi::Severity, const std::string& m) { td.messages->push_back(m); };
    LoadedScene loaded = loadIntoSdf(dev, g, desc);
    REQUIRE(loaded.scene);
    loaded.scene->update(glm::vec3(0.0f, 0.5f, 0.5f));

    gi::ContextDesc cd;
    cd.displayWidth = cd.displayHeight = 64;
    cd.errorCallback = [&td](rhi::Severity, const std::string& m) { td.messages->push_back(m); };
    {  // refusals
        std::unique_ptr<gi::GiContext> plain = gi::GiContext::create(dev, *loaded.scene, cd);
        REQUIRE(plain);
        Error why;
        CHECK(!plain->alphaPassState(rhi::ShaderHandle{}, &why));
        CHECK(why.message.find("ContextFlags::AlphaCache") != std::string::npos);
        CHECK(plain->readAlphaCoverage().empty());
        td.messages->clear();
    }
    cd.flags = gi::ContextFlags::AlphaCache;
    Error createError;
    std::unique_ptr<gi::GiContext> context = gi::GiContext::create(dev, *loaded.scene, cd, &createError);
    INFO(createError.message);
    REQUIRE(context);
    {
        Error why;
        CHECK(!context->alphaPassState(rhi::ShaderHandle{}, &why));
        CHECK(why.message.find("fragment shader") != std::string::npos);
        td.messages->clear();
    }

    rhi::ShaderDesc vd, fd;
    vd.blob = rhi::findShader("sdf_tests/alpha_pass_card.vert");
    fd.blob = rhi::findShader("sdf_tests/alpha_pass_stripes.frag");
    REQUIRE(vd.blob);
    REQUIRE(fd.blob);
    rhi::ShaderHandle vertex = dev.createShader(vd), fragment = dev.createShader(fd);
    const float vertices[] = {-1, 0.05f, 0.013f, 0, 0, 1, 0.05f, 0.013f, 1, 0, 1, 1.45f, 0.013f, 1, 1,
                              -1, 0.05f, 0.013f, 0, 0, 1, 1.45f, 0.013f, 1, 1, -1, 1.45f, 0.013f, 0, 1};
    rhi::BufferDesc bd;
    bd.size = sizeof(vertices);
    bd.usage = rhi::BufferUsage::Vertex;
    bd.debugName = "card vertices";
    rhi::BufferHandle vertexBuffer = dev.createBuffer(bd, vertices);

    const sdf::FieldSnapshot field = loaded.scene->readField();
    auto draw = [&](float share) {
        Error why;
        std::optional<rhi::DrawCallState> s = context->alphaPassState(fragment, &why);
        REQUIRE(s);
        s->vertexShader = vertex;
        s->vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
        s->vertexInputs.push({1, rhi::VertexFormat::Float2, 0, 12});
        s->vertexBuffers.push({vertexBuffer, 0, 20, false});
        static glm::vec4 stripes;
        stripes = glm::vec4(share, 7.3f, 0.0f, 0.0f);  // a period (0.27 m) no cell size divides: no aliasing
        s->bindings.constants.push(rhi::constants(0, stripes));
        rhi::DrawArgs args;
        args.vertexCount = 6;
        REQUIRE(dev.draw(*s, args));
    };
    // Coverage over the cells that hold counts, per cascade: covered fragments over all fragments (the share of
    // the card's surface the alpha test keeps, as the pass sees it).
    auto means = [&](const std::vector<float>& coverage, const std::vector<uint32_t>& fragments, std::vector<uint32_t>* cells) {
        std::vector<double> sum(3, 0.0), weight(3, 0.0);
        cells->assign(3, 0);
        for (uint32_t c = 0; c < 3; ++c)
            for (int z = 0; z < 64; ++z)
                for (int y = 0; y < 64; ++y)
                    for (int x = 0; x < 64; ++x) {
                        const uint32_t brick = field.voxelState(c, {x, y, z});
                        if (brick >= sdf::FieldSnapshot::kUnbuilt - 15) continue;
                        for (uint32_t k = 0; k < 64; ++k)
                            if (coverage[size_t(brick) * 64 + k] >= 0.0f) {
                                const double n = fragments[size_t(brick) * 64 + k];
                                sum[c] += coverage[size_t(brick) * 64 + k] * n;
                                weight[c] += n;
                                ++(*cells)[c];
                            }
                    }
        for (uint32_t c = 0; c < 3; ++c) sum[c] /= std::max(1.0, weight[c]);
        return sum;
    };
    for (float share : {0.25f, 0.5f}) {
        INFO("stripes covered over " << share << " of each period");
        context->reset();
        draw(share);
        std::vector<uint32_t> fragments;
        const std::vector<float> first = context->readAlphaCoverage(&fragments);
        REQUIRE(first.size() == size_t(loaded.scene->brickCapacity()) * 64);
        std::vector<uint32_t> cells;
        const std::vector<double> mean = means(first, fragments, &cells);
        for (uint32_t c = 0; c < 3; ++c) {
            UNSCOPED_INFO("cascade " << c << ": " << cells[c] << " cells with counts, mean coverage " << mean[c]);
            CHECK(cells[c] > (c == 0 ? 1000u : 50u));
            // The fragments (2 per cell side) are point samples of the stripes: 160 across the card in cascade 0
            // (measured within 0.02 of the share), 40 in cascade 2 (within 0.075).
            CHECK(std::abs(mean[c] - share) < (c == 0 ? 0.03 : 0.1));
        }
        draw(share);  // the same pass again: twice the counts, the same shares
        const std::vector<float> second = context->readAlphaCoverage();
        const bool same = second == first;  // (not CHECK(second == first): Catch would print 2M floats)
        CHECK(same);
    }
    // Nothing outside flagged bricks: every cell with counts belongs to a brick the field flagged.
    const std::vector<float> coverage = context->readAlphaCoverage();
    uint32_t unflagged = 0;
    for (size_t i = 0; i < coverage.size(); ++i)
        if (coverage[i] >= 0.0f && !(field.brickAabbs[i / 64] != 0xFFFFFFFFu && (field.brickAabbs[i / 64] & sdf::FieldSnapshot::kAabbAlphaTested))) ++unflagged;
    CHECK(unflagged == 0u);
    dev.destroy(vertexBuffer);
    dev.destroy(vertex);
    dev.destroy(fragment);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("gi alpha pass: coverage of a striped card in every cascade, the same each pass", "[sdf][gi]", alphaPassCoverage)
