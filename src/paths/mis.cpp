#include "paths/mis.h"

#include "geometry/error.h"

namespace tripath {

MisHeuristic parseMisHeuristic(const std::string& name) {
    if (name == "balance") return MisHeuristic::Balance;
    if (name == "power") return MisHeuristic::Power;
    if (name == "none") return MisHeuristic::Uniform;
    throw InputError("unknown MIS heuristic '" + name + "' (balance, power or none)");
}

namespace {

// A zero pdf stands for a delta event; the delta tests below exclude those strategies, and a 1
// keeps the running ratio finite across them.
float remap0(float pdf) { return pdf != 0 ? pdf : 1.0f; }

// The term one competing strategy with pdf ratio r = p_i / p_s adds to the denominator.
float term(float r, MisHeuristic h) {
    switch (h) {
        case MisHeuristic::Balance: return r;
        case MisHeuristic::Power: return r * r;
        case MisHeuristic::Uniform: return r > 0 ? 1.0f : 0.0f;
    }
    return r;
}

}  // namespace

float misWeight(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t, MisHeuristic heuristic,
                StrategySet strategies) {
    float sum = 0;
    // Hand camera vertices z_{t-1}, z_{t-2}, … one by one to the light side: strategy (s+t−i, i),
    // as far as the strategy set enables any (mis.h).
    float r = 1;
    for (int i = t - 1; strategies.readsCameraPdfs(i, s, t); --i) {
        r *= remap0(camera[i].pdfRev) / remap0(camera[i].pdfFwd);
        if (!camera[i].delta && !camera[i - 1].delta && strategies.enabled(s + t - i, i)) sum += term(r, heuristic);
    }
    // Hand light vertices y_{s-1}, … , y_0 to the camera side: strategy (i, s+t−i).
    r = 1;
    for (int i = s - 1; strategies.readsLightPdfs(i, s, t); --i) {
        r *= remap0(light[i].pdfRev) / remap0(light[i].pdfFwd);
        const bool deltaBefore = i > 0 ? light[i - 1].delta : light[0].isDeltaLight();
        if (!light[i].delta && !deltaBefore && strategies.enabled(i, s + t - i)) sum += term(r, heuristic);
    }
    return 1.0f / (1.0f + sum);
}

}  // namespace tripath
