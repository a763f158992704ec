// Helpers shared by the physics tests: rendering at low resolution, scene variants, simple
// statistics.
#pragma once
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

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

}  // namespace tripath::test
