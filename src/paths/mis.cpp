#include "paths/mis.h"

#include <cmath>

#include "geometry/error.h"
#include "paths/kernels.h"

namespace tripath {

MisHeuristic parseMisHeuristic(const std::string& name) {
    if (name == "balance") return MisHeuristic::Balance;
    if (name == "power") return MisHeuristic::Power;
    if (name == "none") return MisHeuristic::Uniform;
    throw InputError("unknown MIS heuristic '" + name + "' (balance, power or none)");
}

namespace {

// The term one competing strategy with pdf ratio r = p_i / p_s adds to the denominator.
float term(float r, MisHeuristic h) {
    switch (h) {
        case MisHeuristic::Balance: return r;
        case MisHeuristic::Power: return r * r;
        case MisHeuristic::Uniform: return r > 0 ? 1.0f : 0.0f;
    }
    return r;
}

// One vertex's pdf as the MIS ratios use it, from the area pdf the walk or the junction recorded
// (0 through a delta lobe) and the vertex g that generated it (null: the emitter sampler). A
// specular chain g → delta … delta → x has no area pdf at its inner vertices, and the area pdf of
// its first vertex is not the density of its far end: the chain maps the solid angle at g onto
// the area at x with a Jacobian no single vertex knows. Étendue is conserved along the chain
// (|cos θ_g| dA_g dω_g = |cos θ_x| dA_x dω_x), so every strategy that crosses it from g's side
// holds that Jacobian times the solid-angle pdf at g, and every one that crosses it from x's side
// the same Jacobian times |cos θ_x| / |cos θ_g| times the solid-angle pdf at x: measured in
// projected solid angle at its two ends, the chain's Jacobian cancels from every ratio. So a
// delta vertex counts with the solid-angle pdf of its non-delta generator, a vertex reached
// through a delta with |cos θ| toward it, and a vertex inside a chain with 1. (Area pdfs through
// the deltas, counted as 1 at the inner vertices, would misjudge caustics: light tracing would be
// weighed down by (d_{g,g+1} / d_{j−1,j})², ~25× on the wall beside smallvcm-5's glass sphere.)
float chainPdf(float recorded, const Vertex& x, bool xDelta, const Vertex* g, bool gDelta) {
    if (!g || (!gDelta && !xDelta)) return recorded;
    const Segment toGenerator(x, *g);
    if (gDelta) return xDelta ? 1.0f : cosine(x, toGenerator.direction());
    return toGenerator.toSolidAngle(recorded, x);
}

// Σ term(p_i / p_base) over the enabled strategies that can sample the path, connections and
// merges, where base is the connection (s, t) of these subpaths and junction: counted itself when
// `countBase` (the caller knows whether it is enabled and possible). Also the ratio of the merge
// at z_{t−1} to the base, which a merge's own weight needs (0 where that merge is not possible).
struct Competition {
    float sum = 0;
    float mergeAtCameraEnd = 0;
};

Competition compete(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t,
                    const Junction& junction, const MisContext& mis, bool countBase) {
    // Each vertex judged as the point it is in THIS path (z_{t−1} is x0 when s = 0). The endpoints
    // a shadow ray joins are interior, and never delta: connect refuses them.
    const int k = s + t - 1;
    auto lightDelta = [&](int i) { return scattersDelta(light[i], i, k); };
    auto cameraDelta = [&](int i) { return scattersDelta(camera[i], k - i, k); };
    const bool pointLight = s > 0 && light[0].isDeltaLight();
    const StrategySet strategies = mis.strategies;
    const Roulette& roulette = mis.roulette;
    const bool merges = strategies.merges();
    // The merge at x_j, j = 1 … k−1 (non-delta): rj is the ratio of the connection with x_j on
    // the camera side, pFromLight x_j's pdf from the light side (as the chain measure counts it).
    auto mergeTerm = [&](float rj, float pFromLight) { return rj * pFromLight * mis.mergeEta; };

    // With running sums, the steps stop where every remaining term is one the subpath's vertex
    // holds: past the two vertices whose pdfs the junction defines, and past those whose roulette
    // factor from the other walk is not yet settled (that walk's index below max(1, depth − 1)).
    const int settled = std::max(1, roulette.depth - 1);
    const int cameraStop = mis.runningSums ? std::max(1, std::min(t - 2, k - settled)) : 1;
    const int lightStop = mis.runningSums ? std::max(0, std::min(s - 2, k - settled)) : 0;

    Competition c;
    if (countBase) c.sum = term(1.0f, mis.heuristic);
    // Hand camera vertices z_{t-1}, z_{t-2}, … one by one to the light side: strategy (s+t−i, i),
    // as far as the strategy set enables any (mis.h). z_i's pdf from the light side is generated
    // by x_{k−i−1}, the (k−i−1)-th vertex of a light walk: z_{i+1}, or y_{s−1} for the last (its
    // pdfs from the junction for the last two); its own by z_{i−1}, the camera walk's (i−1)-th.
    float r = 1;
    for (int i = t - 1; i >= cameraStop && strategies.readsCameraPdfs(i, s, t); --i) {
        const Vertex& x = camera[i];
        const float recorded = i == t - 1 ? junction.cameraEnd : i == t - 2 ? junction.cameraBeforeEnd : x.pdfRev;
        const Vertex* lightSide = i < t - 1 ? &camera[i + 1] : s > 0 ? &light[s - 1] : nullptr;
        // z_i's light-side generator is delta only inside a chain, or at a merge's reference
        // connection, where y_{s−1} may be delta (the merge joins no shadow ray to it).
        const bool lightSideDelta = i < t - 1 ? cameraDelta(i + 1) : s > 0 && lightDelta(s - 1);
        const float other = chainPdf(recorded, x, cameraDelta(i), lightSide, lightSideDelta);
        const float own = chainPdf(x.pdfFwd, x, cameraDelta(i), &camera[i - 1], cameraDelta(i - 1));
        const float qOther = lightSide ? roulette.continuation(*lightSide, k - i - 1) : 1.0f;
        const float qOwn = roulette.continuation(camera[i - 1], i - 1);
        if (merges && k - i >= 1 && !cameraDelta(i)) {  // x_{k−i} interior, non-delta
            const float m = mergeTerm(r, other * qOther);
            if (i == t - 1) c.mergeAtCameraEnd = m;
            c.sum += term(m, mis.heuristic);
        }
        r *= (other * qOther) / (own * qOwn);
        if (!cameraDelta(i) && !cameraDelta(i - 1) && strategies.enabled(s + t - i, i)) c.sum += term(r, mis.heuristic);
    }
    if (cameraStop > 1) c.sum += term(r, mis.heuristic) * camera[cameraStop - 1].misSum;
    // Hand light vertices y_{s-1}, … , y_0 to the camera side: strategy (i, s+t−i). y_i's pdf from
    // the camera side is generated by x_{i+1}, the (k−i−1)-th vertex of a camera walk: y_{i+1}, or
    // z_{t−1} for the last (pdfs from the junction for the last two); its own by y_{i−1} (y_0's by
    // the emitter sampler: a delta for a point light, which no walk can hit, and common to every
    // strategy that can sample the path).
    r = 1;
    for (int i = s - 1; i >= lightStop && strategies.readsLightPdfs(i, s, t); --i) {
        const Vertex& x = light[i];
        const float recorded = i == s - 1 ? junction.lightEnd : i == s - 2 ? junction.lightBeforeEnd : x.pdfRev;
        const Vertex& cameraSide = i < s - 1 ? light[i + 1] : camera[t - 1];
        const bool cameraSideDelta = i < s - 1 ? lightDelta(i + 1) : cameraDelta(t - 1);
        const float other = chainPdf(recorded, x, lightDelta(i), &cameraSide, cameraSideDelta);
        const float own = i > 0 ? chainPdf(x.pdfFwd, x, lightDelta(i), &light[i - 1], lightDelta(i - 1))
                                : (pointLight ? 1.0f : x.pdfFwd);
        const float qOther = roulette.continuation(cameraSide, k - i - 1);
        const float qOwn = i > 0 ? roulette.continuation(light[i - 1], i - 1) : 1.0f;
        // After this step r is the ratio of the connection with y_i = x_i on the camera side, so
        // the merge at y_i adds r times x_i's light-side pdf (own · qOwn) times η.
        r *= (other * qOther) / (own * qOwn);
        if (merges && i >= 1 && !lightDelta(i)) c.sum += term(mergeTerm(r, own * qOwn), mis.heuristic);
        const bool possible = i > 0 ? !lightDelta(i) && !lightDelta(i - 1) : !pointLight;
        if (possible && strategies.enabled(i, s + t - i)) c.sum += term(r, mis.heuristic);
    }
    if (lightStop > 0) c.sum += term(r, mis.heuristic) * light[lightStop - 1].misSum;
    return c;
}

}  // namespace

bool canUseRunningSums(const MisContext& mis) {
    return mis.strategies.summable() && mis.heuristic != MisHeuristic::Uniform;
}

// The running sums: the terms compete() adds beyond its explicit steps, summed from the subpath's
// start. They hold the factors a long path gives (the other walk's roulette settled, every vertex
// here interior). With a_m = term(other_m / own_m), m's pdf ratio as compete() forms it:
//   camera subpath  W_m = a_m W_{m−1} + [merge at z_m] term(other_m η) + [connection at m] a_m,
//                   W_0 = 0 (the sensor);
//   light subpath   V_m = a_m (V_{m−1} + [merge at y_m] term(own_m η) + [connection at m]),
//                   V_{−1} = 0;
// and the terms of all vertices up to j, seen from a junction whose ratios beyond j multiply to
// r, add up to term(r) · W_j or term(r) · V_j.
void recordRunningSums(std::span<Vertex> path, bool light, const MisContext& mis) {
    if (!mis.runningSums) return;
    const int n = static_cast<int>(path.size());
    const StrategySet set = mis.strategies;
    const MisHeuristic h = mis.heuristic;
    const bool merges = set.merges();
    auto delta = [&](int i) { return i > 0 && path[i].delta; };  // vertex 0 emits or senses
    float sum = 0;
    for (int m = 0; m + 2 < n; ++m) {
        Vertex& x = path[m];
        const float other = chainPdf(x.pdfRev, x, delta(m), &path[m + 1], delta(m + 1)) * path[m + 1].continuation;
        if (light) {
            const bool pointLight = x.isDeltaLight();
            const float own = m > 0 ? chainPdf(x.pdfFwd, x, delta(m), &path[m - 1], delta(m - 1)) *
                                          mis.roulette.continuation(path[m - 1], m - 1)
                                    : (pointLight ? 1.0f : x.pdfFwd);
            const bool possible = m > 0 ? !delta(m) && !delta(m - 1) : !pointLight;
            const float merge = merges && m >= 1 && !delta(m) ? term(own * mis.mergeEta, h) : 0.0f;
            const float connection = possible && set.enabled(m, 2) ? 1.0f : 0.0f;
            sum = term(other / own, h) * (sum + merge + connection);
        } else if (m > 0) {
            const float own = chainPdf(x.pdfFwd, x, delta(m), &path[m - 1], delta(m - 1)) *
                              mis.roulette.continuation(path[m - 1], m - 1);
            const float a = term(other / own, h);
            const float merge = merges && !delta(m) ? term(other * mis.mergeEta, h) : 0.0f;
            const float connection = !delta(m) && !delta(m - 1) && set.enabled(1, m) ? a : 0.0f;
            sum = a * sum + merge + connection;
        }
        x.misSum = sum;
    }
}

// FirstHitMerging's one strategy per path: s = 0 or the merge at z_{t−1}, for a camera walk that
// reached z_{t−1} through deltas alone (its walks stop there; this keeps the weight right for any caller).
static MisWeight firstHitWeight(std::span<const Vertex> camera, int t) {
    for (int i = 1; i < t - 1; ++i)
        if (!camera[i].delta) return {0.0f, false};
    return {1.0f, false};
}

MisWeight misWeight(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t,
                    const Junction& junction, const MisContext& mis) {
    if (mis.strategies.uniqueStrategy()) return firstHitWeight(camera, t);
    const Competition c = compete(light, s, camera, t, junction, mis, true);
    if (!std::isfinite(c.sum)) return {0.0f, true};
    return {1.0f / c.sum, false};
}

MisWeight mergeWeight(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t,
                      const Junction& junction, const MisContext& mis) {
    if (mis.strategies.uniqueStrategy()) return firstHitWeight(camera, t);
    // The reference: the connection (s−1, t) that holds the merged vertex on the camera side,
    // counted if it is enabled and possible (z_{t−1} never scatters through a delta lobe -- merges
    // happen only where it does not -- but y_{s−2} may).
    const int k = s + t - 2;
    const bool base = mis.strategies.enabled(s - 1, t) && !scattersDelta(light[s - 2], s - 2, k);
    const Competition c = compete(light, s - 1, camera, t, junction, mis, base);
    if (!std::isfinite(c.sum)) return {0.0f, true};
    if (!(c.mergeAtCameraEnd > 0)) return {0.0f, false};  // a zero pdf: this merge cannot sample the path
    return {term(c.mergeAtCameraEnd, mis.heuristic) / c.sum, false};
}

}  // namespace tripath
