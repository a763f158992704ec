// Multiple importance sampling over the strategies an integrator enables (docs/design.md §1).
//
// A full path x0 … xk can be produced by strategy (s, t): s vertices from the light, t from the
// camera, s + t = k + 1. With p_i the pdf of strategy (i, k+1−i), the balance heuristic weight of
// (s,t) is p_s / Σ_i p_i over the ENABLED strategies that can sample the path. The ratios
// p_i / p_s follow from the per-vertex area pdfs alone: moving one vertex from the camera side to
// the light side multiplies the pdf by pdfRev / pdfFwd of that vertex (Veach §10.2), so
//     p_{s+1} / p_s = pdfFwd-by-light(x_s) / pdfFwd-by-camera(x_s)
// and so on outward.
//
// Each area pdf includes the roulette factor of the vertex that generated it (roulette.h): q of
// that vertex when its index in the generating walk is past the start depth. The walks record
// the bare pdfs; the weight applies the factors, because a vertex's index in the walk from the
// other end depends on the strategy.
//
// Deltas are flags, never read from a zero pdf. A vertex scatters through a delta lobe (mirror,
// glass) only where it scatters: x0 emits and xk senses, so neither is ever a delta scatterer,
// whatever its material -- an emissive mirror reached by a camera walk is x0 of the s = 0 path, and
// NEE to the same point judges it the same way. A strategy that joins its subpaths at a delta
// scatterer, or hits a delta light (point, spot, directional), is impossible and drops out. An area
// pdf is a delta exactly when the vertex that generates it is a delta scatterer (or, for x0, a
// delta light's position or direction): such a factor is common to every strategy that can sample
// the path, and the chain of delta vertices it belongs to (between two non-delta ones) is measured
// in projected solid angle at its ends instead, which makes every ratio across it exact (chainPdf
// in mis.cpp). A zero pdf that is not a delta makes the strategies that need it impossible, and
// nothing else.
//
// MIS reads the subpaths and never writes them: what a strategy defines at its junction (the
// reverse pdfs of the two endpoints and of their predecessors) comes in a Junction. A ratio that
// is not finite (a pdf the sampler produced but the points' recomputation rounds to 0) gives the
// weight 0 and is reported, never a NaN.
//
// Merges (merge.h) join the same sum. A merge at interior vertex x_j (non-delta) has the pdf
// p_j · p_light(x_j) · η = p_{j+1} · p_camera(x_j) · η, where p_j is the connection with x_j on the
// camera side and η = π r² N_L: so the walk that passes x_j from one side to the other adds the
// merge's term on the way, from the ratio it already holds and x_j's pdf from the other side. A
// merge's own weight is taken with the connection that holds its merged vertex on the camera side
// as the reference. Chains of deltas keep their projected-solid-angle measure: x_j's pdf from
// across a chain is the chain measure's, and every strategy, merges included, crosses each chain
// exactly once, so the chains' Jacobians still cancel from every ratio.
//
// Cost. The weight walks outward from the junction, one ratio per vertex: O(k) per connection.
// The loops stop at the last strategy the set enables: one ratio for PT, none for LT. For the
// unbounded sets (bdpt, vcm, bpm) under the balance or power heuristic the walk is cut short:
// every term beyond the first few vertices is a product of ratios that depend on one subpath
// alone, so each vertex can carry the sum of all of them from its subpath's start (misSum, the
// running sums of Georgiev et al.'s "Implementing Vertex Connection and Merging", here in this
// file's pdf terms), recorded once per subpath after its walk (recordRunningSums). The weight
// then steps over the vertices whose pdfs the junction defines (two) and those whose roulette
// factor depends on the other walk's length (up to --rr-depth), and takes the rest from the
// vertex where it stopped: O(1) in the path length. The O(k) walk stays as the reference the
// tests hold the running sums to, and serves the uniform heuristic, the bounded sets, and any
// path whose running sums leave the float range (where the walk's own products stay in it).
#pragma once
#include <array>
#include <span>

#include "paths/pass_constants.h"
#include "paths/roulette.h"
#include "paths/vertex.h"

namespace tripath {

enum class MisHeuristic { Balance, Power, Uniform };

// Which pdfs a subpath walk records for MIS: every vertex's pdfFwd and pdfRev, only the pdfFwd
// of vertices that lie on an emitter, or none.
enum class WalkPdfs { All, AtEmitters, None };

// Which strategies are enabled: a plain description that names no integrator (each integrator
// says in its own file which set it is). The default is every connection and no merge.
struct StrategySet {
    static constexpr int kUnbounded = 1 << 20;
    // Connections: the box s ≤ maxS, minT ≤ t ≤ maxT. s = 0: the camera walk hits an emitter; s = 1:
    // next-event estimation (at a camera vertex on a surface, t ≥ 2, for a set without t = 1:
    // joining an emitter point straight to the sensor is light tracing's splat); t = 1: the light
    // subpath joined to the sensor. t = 0 is impossible with a pinhole and never enabled.
    int maxS = kUnbounded, minT = 1, maxT = kUnbounded;
    // Whether the box's connections with s, t ≥ 2 are enabled: without them, a box that holds s ≤ 1
    // and t = 1 enables path tracing and light tracing alone.
    bool connects = true;
    // Whether the unidirectional strategies (s ≤ 1 with t ≥ 2: the camera walk's hits on emitters
    // and its next-event estimates) are enabled: a set without them, connections and merges keeps
    // of a camera sample only the sensor, for light tracing.
    bool unidirectional = true;
    // Merges of light vertex y_{s−1} with camera vertex z_{t−1} (s, t ≥ 2): none; at every
    // non-delta camera vertex; or only where the camera walk first meets a non-delta surface, which
    // also counts s = 0 only for camera walks through deltas alone, so that every path is sampled
    // by exactly one strategy.
    enum class Merging { None, EveryVertex, FirstNonDelta };
    Merging merging = Merging::None;

    bool operator==(const StrategySet&) const = default;
    bool enabled(int s, int t) const {
        return s <= maxS && t >= minT && t <= maxT && (connects || s <= 1 || t == 1) &&
               (unidirectional || s >= 2 || t == 1);
    }
    bool merges() const { return merging != Merging::None; }
    // Whether a camera sample needs its camera walk: some strategy with t ≥ 2 is enabled.
    bool walksCamera() const { return maxT >= 2 && (merges() || unidirectional || (connects && maxS >= 2)); }
    // Every path the set samples, it samples with exactly one strategy: its weight is 1.
    bool uniqueStrategy() const { return merging == Merging::FirstNonDelta; }
    // Whether the weights can use running sums (mis.h): every strategy beyond the junction is
    // enabled or disabled by its vertex count on one side alone (all connections; or s = 0 only).
    bool summable() const {
        return !uniqueStrategy() && unidirectional && ((connects && maxS == kUnbounded && minT == 1 && maxT == kUnbounded) || maxS == 0);
    }

    // The weight of (s, t) walks outward from the connection through strategies (s+t−i, i) on the
    // camera side and (i, s+t−i) on the light side, multiplying one pdf ratio per vertex, and needs
    // to go only as far as the last enabled one (or further, where connections are off). So it
    // reads the pdfs of camera vertex i only when i ≥ minT and s + t − i ≤ maxS, and of light
    // vertex i only when s + t − i ≤ maxT (the light side's t only grows). With merges, a merge
    // may be enabled at any vertex: every pdf is read. `connect` sets no other pdf, and the walks
    // record no other.
    bool readsCameraPdfs(int i, int s, int t) const {
        if (uniqueStrategy()) return false;
        return i < t && (merges() ? i >= 1 : i >= minT && s + t - i <= maxS);
    }
    bool readsLightPdfs(int i, int s, int t) const {
        if (uniqueStrategy()) return false;
        return i >= 0 && i < s && (merges() || s + t - i <= maxT);
    }
    // What that leaves the walks to record. Camera vertex i's pdfs are read by (s, t) = (0, i+1)
    // when maxS ≥ 1 -- a non-zero contribution only if the vertex lies on an emitter -- and by
    // some (s ≥ 1, t) or (s, t ≥ i+2) only when maxS ≥ 2. Light vertex i's are read by (i+1, 1)
    // and beyond when maxT ≥ 2; nothing plays the part of s = 0 (t = 0 is never enabled).
    WalkPdfs cameraWalkPdfs() const {
        if (uniqueStrategy()) return WalkPdfs::None;
        if (merges()) return WalkPdfs::All;
        return maxS >= 2 ? WalkPdfs::All : maxS == 1 ? WalkPdfs::AtEmitters : WalkPdfs::None;
    }
    WalkPdfs lightWalkPdfs() const {
        if (uniqueStrategy()) return WalkPdfs::None;
        return merges() || maxT >= 2 ? WalkPdfs::All : WalkPdfs::None;
    }
};

// What strategy (s, t) defines where it joins its subpaths: the area pdfs with which each
// endpoint would be generated by the other subpath, and those of the endpoints' predecessors
// generated through the endpoints (Veach §10.2). `connect` fills the ones the strategy set's
// weight reads (StrategySet::readsCameraPdfs / readsLightPdfs); the others stay unread.
struct Junction {
    float cameraEnd = 0;        // pdfRev of z_{t-1}: from y_{s-1}, or the emitter sampler (s = 0)
    float cameraBeforeEnd = 0;  // pdfRev of z_{t-2}: from z_{t-1}, reached from the light side
    float lightEnd = 0;         // pdfRev of y_{s-1}: from z_{t-1}
    float lightBeforeEnd = 0;   // pdfRev of y_{s-2}: from y_{s-1}, reached from the camera side
};

// The one test of "x_j scatters through a delta lobe" for vertex v at index j of a path of k
// segments: only interior vertices scatter, so x0 (which emits) and xk (the sensor) never do,
// whatever their material. Light vertex i is x_i; camera vertex i is x_{k−i}.
inline bool scattersDelta(const Vertex& v, int j, int k) { return j > 0 && j < k && v.delta; }

struct MisWeight {
    float value = 0;
    bool guarded = false;  // a pdf ratio was not finite: the weight was set to 0
};

// The classes of strategies whose numbers per pass a render may change independently of one
// another (integrators/auto.cpp): the unidirectional ones, s ≤ 1 with t ≥ 2 (the camera walk hits
// an emitter, next-event estimation), whatever the light phase; the connections, s, t ≥ 2, of a
// camera subpath with one light subpath; light tracing, t = 1, N_L joins to the sensor per pass;
// and the merges, whose factor η = π r² N_L grows with the light paths too.
enum class TechniqueClass { Unidirectional, Connection, LightTracing, Merge };
inline constexpr int kTechniqueClasses = 4;
inline TechniqueClass techniqueClass(int s, int t, bool merge) {
    if (merge) return TechniqueClass::Merge;
    if (t == 1) return TechniqueClass::LightTracing;
    return s <= 1 ? TechniqueClass::Unidirectional : TechniqueClass::Connection;
}
using TechniqueSums = std::array<float, kTechniqueClasses>;

// The strategies a render measures, whichever of them its pass enables (integrators/auto.cpp):
// connections and merges then give each path's technique sums over this set, with this merge
// factor (Connection::techniques), which a pass that does not merge needs all the same, and no
// weight: the render weighs each path by its classes (classWeight), pixel by pixel.
struct TechniqueMeasure {
    bool on = false;
    StrategySet strategies;
    float mergeEta = 0;
};

// What a weight depends on besides the path: the heuristic, the strategies the integrator enables,
// and the roulette its walks play (each strategy's pdf includes its walks' continuation factors);
// and the pass's constants: N_L, which the sensor's pdf in t = 1 connections is over, and with
// merges the merge factor η = π r² N_L: a merge at x_j has the pdf of the connection with x_j on
// the camera side times x_j's pdf from the light side times η (merge.h).
struct MisContext {
    MisHeuristic heuristic = MisHeuristic::Power;
    StrategySet strategies;
    Roulette roulette;
    PassConstants constants;
    // The subpaths carry running sums recorded for this context (recordRunningSums): weights in
    // O(1). Only for a summable set under the balance or power heuristic.
    bool runningSums = false;
    TechniqueMeasure measure;
    // The strategies whose pdfs a junction must define: the enabled ones, and the measured ones.
    const StrategySet& junctionStrategies() const { return measure.on ? measure.strategies : strategies; }
    // This context as the technique sums read it: the measured set and merge factor.
    MisContext measured() const {
        MisContext m = *this;
        m.strategies = measure.strategies;
        m.constants.mergeEta = measure.mergeEta;
        return m;
    }
};

// Whether a context may use running sums: the set is summable and the heuristic multiplicative.
bool canUseRunningSums(const MisContext& mis);

// Records misSum at each vertex of a finished subpath (a light subpath if `light`, else a camera
// subpath), for the weights of context `mis`; a no-op unless mis.runningSums. Vertex i's sum needs
// the pdfs recorded up to vertex i+2: the last two get none, and no weight reads them.
void recordRunningSums(std::span<Vertex> path, bool light, const MisContext& mis);

// Weight of connection (s, t) for the path light[0..s) + camera[0..t) reversed.
MisWeight misWeight(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t,
                    const Junction& junction, const MisContext& mis);
// Weight of the merge of light[s−1] with camera[t−1] (s, t ≥ 2) for the path light[0..s−1) +
// camera[0..t) reversed, of k = s + t − 2 segments: camera[t−1] stands for the merged vertex.
// `junction` is that of the connection (s−1, t) joining light[s−2] to camera[t−1] (merge.cpp).
MisWeight mergeWeight(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t,
                      const Junction& junction, const MisContext& mis);

// The balance heuristic's denominator of a path split by class: Σ p_i / p over the strategies of
// mis's set that can sample the path, p being the pdf of the strategy that sampled it (the
// connection (s, t) or the merge of light[s−1] with camera[t−1], whose junction misWeight or
// mergeWeight is given), that strategy included. The pdfs are those of mis's constants: a
// render that would trace N_L' light paths instead of N_L, or connect c' times instead of once,
// has the denominator Σ_class n'_class / n_class · sums[class] (integrators/auto.cpp). Whatever
// mis's heuristic, the sums are the balance heuristic's, and the full walk's (no running sums).
// All zero if that strategy cannot sample the path.
TechniqueSums connectionTechniqueSums(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t,
                                      const Junction& junction, const MisContext& mis);
TechniqueSums mergeTechniqueSums(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t,
                                 const Junction& junction, const MisContext& mis);

// Σ_class factors[class] · sums[class]: the balance heuristic's denominator of a path, over the
// pdf of the strategy that sampled it, for a render that runs factors[class] times as many samples
// of each class as the technique sums were measured with (0: a class it does not run). Inline:
// auto's measuring passes take it for every candidate of every contribution.
inline float techniqueDenominator(const TechniqueSums& factors, const TechniqueSums& sums) {
    float d = 0;
    for (int c = 0; c < kTechniqueClasses; ++c) d += factors[c] * sums[c];
    return d;
}
// The balance heuristic's weight of a path sampled by a strategy of class `sampled`, in a render
// with those factors: factors[sampled] / techniqueDenominator; 0 where the render does not run the
// class, and 0 and guarded where the sums are not finite.
MisWeight classWeight(const TechniqueSums& factors, TechniqueClass sampled, const TechniqueSums& sums);

}  // namespace tripath
