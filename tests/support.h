// Helpers shared by the physics tests: rendering at low resolution, scene variants, simple
// statistics, and independent runs measured block by block and compared with Welch's test.
#pragma once
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/vec.h"
#include "evaluation/bias.h"
#include "scenes/builtin_scenes.h"
#include "integrators/render.h"
#include "requests/render_request.h"

namespace tripath::test {

// The library's render request (requests/render_request.h) at the tests' usual size: pt,
// 16×16 pixels, 4 passes; tests set what they need on top.
inline RenderRequest smallRequest() {
    RenderRequest r;
    r.integrator = "pt";
    r.width = r.height = 16;
    r.spp = 4;
    return r;
}

// Renders a scene built by the caller (at r.width x r.height) as the command line would.
inline RenderResult renderScene(const Scene& scene, const RenderRequest& r) {
    const auto integrator = makeIntegrator(r.integrator, integratorSettings(r));
    return render(scene, *integrator, renderSettings(r));
}

inline RenderResult renderDesc(const SceneDesc& desc, const RenderRequest& r) {
    const Scene scene(desc, r.width, r.height);
    return renderScene(scene, r);
}

// `desc` with every triangle cut into n² coplanar pieces (corners a + (b−a)·i/n + (c−a)·j/n, so
// a face in an axis-aligned plane stays exactly in it). Embree builds a BVH of fewer than 1024
// primitives on one thread, and partitions sets of fewer than 3072 sequentially, whatever the
// threads it is given: `contact` (48 triangles) needs this to reach its parallel code.
inline SceneDesc tessellated(SceneDesc desc, int n) {
    for (MeshDesc& m : desc.meshes) {
        MeshDesc cut;
        cut.name = m.name;
        cut.material = m.material;
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            const Vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                       c = m.positions[m.indices[t + 2]];
            const auto corner = [&](int i, int j) {
                cut.positions.push_back(a + (b - a) * (float(i) / n) + (c - a) * (float(j) / n));
                return static_cast<uint32_t>(cut.positions.size() - 1);
            };
            for (int i = 0; i < n; ++i)
                for (int j = 0; i + j < n; ++j) {
                    const uint32_t p = corner(i, j), q = corner(i + 1, j), r = corner(i, j + 1);
                    cut.indices.insert(cut.indices.end(), {p, q, r});
                    if (i + j + 1 < n) cut.indices.insert(cut.indices.end(), {q, corner(i + 1, j + 1), r});
                }
        }
        m = std::move(cut);
    }
    return desc;
}

// Builds the scene (and so its Embree BVH) inside an arena of `threads` threads: Embree builds
// with the threads of the arena it is called from.
inline std::unique_ptr<Scene> buildWithThreads(const SceneDesc& desc, int width, int height, int threads) {
    std::unique_ptr<Scene> scene;
    tbb::task_arena(threads).execute([&] { scene = std::make_unique<Scene>(desc, width, height); });
    return scene;
}

// Mean of one channel (or of all three, c = -1) over a block of pixels.
inline double blockMean(const Image& img, int x0, int y0, int w, int h, int c = -1) {
    double sum = 0;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x)
            for (int k = 0; k < 3; ++k)
                if (c < 0 || c == k) sum += img.at(x, y)[k];
    return sum / (double(w) * h * (c < 0 ? 3 : 1));
}

// Sample mean and standard error of the mean.
struct MeanError {
    double mean = 0, stderr_ = 0;
};
inline MeanError meanAndError(const std::vector<double>& v) {
    MeanError m;
    for (double x : v) m.mean += x;
    m.mean /= v.size();
    double var = 0;
    for (double x : v) var += (x - m.mean) * (x - m.mean);
    var /= (v.size() - 1);
    m.stderr_ = std::sqrt(var / v.size());
    return m;
}

// ---- independent runs, measured by block ---------------------------------------------------

// A rectangle of pixels; with a mask (one entry per pixel of the image, row by row), only the
// pixels of the rectangle that the mask keeps.
struct Block {
    int x = 0, y = 0, w = 0, h = 0;
    std::vector<bool> mask = {};
};

// The nx × ny blocks that tile a width × height image, row by row.
inline std::vector<Block> blockGrid(int width, int height, int nx, int ny) {
    std::vector<Block> blocks;
    const int w = width / nx, h = height / ny;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) blocks.push_back({i * w, j * h, w, h});
    return blocks;
}

// What a block's mean is taken of, pixel by pixel: luminance or average (core/vec.h).
using PixelValue = float (*)(Spectrum);

// Mean of `value` over the pixels of a block (0 when its mask keeps none).
inline double blockMean(const Image& img, const Block& b, PixelValue value) {
    double sum = 0;
    int n = 0;
    for (int y = b.y; y < b.y + b.h; ++y)
        for (int x = b.x; x < b.x + b.w; ++x) {
            if (!b.mask.empty() && !b.mask[static_cast<size_t>(y) * img.width + x]) continue;
            const float* p = img.at(x, y);
            sum += value(Spectrum(p[0], p[1], p[2]));
            ++n;
        }
    return n > 0 ? sum / n : 0.0;
}

// `runs` independent renders of `scene` as `r` asks, with seeds firstSeed, firstSeed + 1, …; none
// may drop a sample (a NaN or infinite contribution).
inline std::vector<Image> renderRuns(const Scene& scene, RenderRequest r, int runs, uint64_t firstSeed) {
    std::vector<Image> images;
    for (int run = 0; run < runs; ++run) {
        r.seed = firstSeed + static_cast<uint64_t>(run);
        const RenderResult result = renderScene(scene, r);
        EXPECT_EQ(result.droppedSamples, 0u) << scene.name() << ", " << r.integrator << ", seed " << r.seed;
        images.push_back(result.image());
    }
    return images;
}

// The samples a block comparison works on: runs[block][run], a block's mean in each run.
using BlockRuns = std::vector<std::vector<double>>;

// The means of `value` over each block in each of renderRuns(scene, r, runs, firstSeed).
inline BlockRuns blockRuns(const Scene& scene, const RenderRequest& r, int runs, uint64_t firstSeed,
                           const std::vector<Block>& blocks, PixelValue value = luminance) {
    BlockRuns out(blocks.size());
    for (const Image& img : renderRuns(scene, r, runs, firstSeed))
        for (size_t k = 0; k < blocks.size(); ++k) out[k].push_back(blockMean(img, blocks[k], value));
    return out;
}

// The noise ceiling of an agreement test: a renderer whose run means spread so that the standard
// error of a block's mean exceeds this share of the signal (the block's own mean, or the mean
// level of the blocks compared where that is larger: a dark block is judged against the image)
// makes the test fail, since a bias smaller than a few such errors would pass unseen.
inline constexpr double kNoiseCeiling = 0.1;

// Whether the standard errors of `a` and `b` stay below the noise ceiling's share of `signal`;
// a failure names the one that does not.
inline void expectBelowNoiseCeiling(const MeanError& a, const MeanError& b, double signal, const std::string& what) {
    EXPECT_LE(a.stderr_, kNoiseCeiling * signal) << what << ": the first is too noisy to judge by";
    EXPECT_LE(b.stderr_, kNoiseCeiling * signal) << what << ": the second is too noisy to judge by";
}

// Block-by-block comparisons of two renderers' runs, judged together: Welch's t-test of each
// block's run means (evaluation/bias.h), Holm-corrected over every comparison made, so that the chance
// of any false alarm between unbiased renderers is at most alpha (if the run means are normal);
// and each block's standard errors held under the noise ceiling of the comparisons' mean level.
class BlockAgreement {
public:
    // One block: `a` and `b` are its means over the runs of each renderer.
    void compare(const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
        comparisons_.push_back({what, meanAndError(a), meanAndError(b), welchTest(a, b)});
    }
    // Every block of `a` against the same block of `b`.
    void compare(const BlockRuns& a, const BlockRuns& b, const std::string& what) {
        for (size_t block = 0; block < a.size(); ++block)
            compare(a[block], b.at(block), what + ", block " + std::to_string(block));
    }
    void expectNoBias(double alpha = 0.01) const {
        std::vector<double> p;
        double signal = 0;
        for (const Comparison& c : comparisons_) {
            p.push_back(c.test.p);
            signal += std::max(std::abs(c.a.mean), std::abs(c.b.mean)) / double(comparisons_.size());
        }
        for (const Comparison& c : comparisons_)
            expectBelowNoiseCeiling(c.a, c.b, std::max({signal, std::abs(c.a.mean), std::abs(c.b.mean)}), c.what);
        const std::vector<bool> biased = holmSignificant(p, alpha);
        for (size_t i = 0; i < comparisons_.size(); ++i) {
            const Comparison& c = comparisons_[i];
            EXPECT_FALSE(biased[i]) << c.what << ": " << c.a.mean << " ± " << c.a.stderr_ << " against " << c.b.mean
                                    << " ± " << c.b.stderr_ << " (t = " << c.test.t << ", p = " << c.test.p << ")";
        }
    }

private:
    struct Comparison {
        std::string what;
        MeanError a, b;
        WelchTest test;
    };
    std::vector<Comparison> comparisons_;
};

// pt and lt each render scenes `a` and `b`, which must be lit alike, in 16 runs of 64 samples per
// pixel of `r` (its size), block by block over 2 × 2 blocks: one agreement per integrator.
inline void expectLitAlikeByPtAndLt(const Scene& a, const Scene& b, RenderRequest r, const std::string& what) {
    const std::vector<Block> blocks = blockGrid(r.width, r.height, 2, 2);
    for (const char* integrator : {"pt", "lt"}) {
        r.integrator = integrator;
        r.spp = 64;
        BlockAgreement agreement;
        agreement.compare(blockRuns(a, r, 16, 500, blocks), blockRuns(b, r, 16, 600, blocks),
                          std::string(integrator) + ": " + what);
        agreement.expectNoBias();
    }
}

}  // namespace tripath::test
