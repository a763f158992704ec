// The research scenes shipped in scenes/ (scenes/README.md: veach-bidir, lamp-caustic,
// box-light-top, water-caustic), converted by scripts/convert-literature-scenes.py. The benchmark's
// documented scene set includes them, so each must load as the converter meant it (its own camera,
// emitters, no feature the loader drops with a warning) and light its image under bdpt: a file
// broken on the way (a truncated buffer, an emitter or the camera lost, materials the loader
// refuses) fails here rather than in the middle of a benchmark.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/vec.h"
#include "geometry/scene.h"
#include "io/gltf_loader.h"
#include "support.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kLiteratureScenes = {"veach-bidir", "lamp-caustic", "box-light-top",
                                                    "water-caustic"};

bool hasEmitter(const SceneDesc& desc) {
    for (const Material& m : desc.materials)
        if (!isBlack(m.emission)) return true;
    return !desc.lights.empty();
}

TEST(LiteratureScenes, EachLoadsCleanlyAndBdptLightsItsImage) {
    for (const std::string& name : kLiteratureScenes) {
        const fs::path path = fs::path(TRIPATH_SOURCE_DIR) / "scenes" / (name + ".gltf");
        std::vector<std::string> warnings;
        SceneDesc desc;
        ASSERT_NO_THROW(desc = loadGltf(path.string(), [&](const std::string& w) { warnings.push_back(w); }))
            << path;
        EXPECT_TRUE(warnings.empty()) << name << ": " << (warnings.empty() ? "" : warnings.front());
        EXPECT_TRUE(desc.camera.present) << name << ": the scene's own camera is missing";
        EXPECT_TRUE(hasEmitter(desc)) << name;

        RenderRequest r = test::smallRequest();
        r.integrator = "bdpt";
        r.spp = 8;
        const Scene scene(desc, r.width, r.height, [](const std::string&) {});
        const RenderResult result = test::renderScene(scene, r);
        EXPECT_EQ(result.droppedSamples, 0u) << name;
        const std::vector<float>& rgb = result.image().rgb;
        int lit = 0;
        for (size_t i = 0; i < rgb.size(); i += 3) {
            for (size_t c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(rgb[i + c]) && rgb[i + c] >= 0) << name;
            lit += rgb[i] + rgb[i + 1] + rgb[i + 2] > 0;
        }
        // Every camera looks into a closed, lit room: most pixels see light within 8 samples.
        EXPECT_GT(lit, static_cast<int>(rgb.size() / 3) / 2) << name << ": " << lit << " lit pixels";
        RecordProperty(name + " lit pixels", lit);
    }
}

}  // namespace
}  // namespace tripath
