// What every connection and merge of one pass shares besides the strategies: N_L, the light
// paths the pass traces, its merge radius r, and the merge factor η = π r² N_L. The light phase
// makes them once per pass (integrators/light_phase.h) and they travel with the pass's MIS context
// (mis.h), so every kernel reads the same resolved N_L: the sensor's per-pixel pdf is over it
// (kernels.h), a splat counts 1/N_L, and a merge's pdf carries η (merge.h).
#pragma once
#include "core/vec.h"

namespace tripath {

struct PassConstants {
    double lightPaths = 0;  // N_L ≥ 1 (PixelSampleIntegrator::lightPaths decides it)
    float radius = 0;       // the merge radius r; 0 where the pass does not merge
    float mergeEta = 0;     // η = π r² N_L; 0 where the pass does not merge
};

// The constants of a pass that traces `lightPaths` light paths and merges within `radius` (0: no merging).
inline PassConstants passConstants(double lightPaths, float radius) {
    return {lightPaths, radius, static_cast<float>(kPi * double(radius) * radius * lightPaths)};
}

}  // namespace tripath
