// Vertex merging (Georgiev, Křivánek, Davidovič, Slusallek 2012; Hachisuka, Pantaleoni, Jensen
// 2012): a light vertex y_{s−1} that landed within radius r of camera vertex z_{t−1} stands in
// for the light walk having generated z_{t−1} itself.
//
// In the three-point form. The merged path is x0 … x_{j−1} = y0 … y_{s−2}, x_j = z_{t−1}, and
// x_{j+1} … x_k = z_{t−2} … z0: s − 1 light vertices, t camera vertices, k = s + t − 2 segments.
// Its contribution is the usual product of kernels,
//     f(x̄) = ε g · Π ρ g · W,
// and the merge generates it with the pdf of the connection (s−1, t) -- the light prefix to
// y_{s−2} and the camera prefix to z_{t−1} -- times the probability that one of the pass's N_L
// light walks, having reached y_{s−2}, puts its next vertex in the disc of radius r around z_{t−1}:
//     p_merge(x̄) ≈ p_{s−1,t}(x̄) · p_A(x_j | y_{s−2}) · π r² · N_L,
// p_A(x_j | y_{s−2}) being the area pdf of the light walk's step (y_{s−1}'s pdfFwd, read at the
// light vertex: within r the density is taken as constant, which is the merge's bias). So
//     f / p_merge = [f-prefix / p of the light walk to y_{s−2}] · ε-or-ρ(… → y_{s−2} → x_j) g(y_{s−2}, x_j) / p_A(x_j)
//                   · ρ(y_{s−2} → x_j → z_{t−2}) · [the camera prefix's f / p] / (π r² N_L),
// and the first bracket times the light step's g / p_A is y_{s−1}'s beta (the walk's throughput
// on arrival), the last is z_{t−1}'s beta: the estimate is
//     beta(z_{t−1}) · ρ(y_{s−2} → z_{t−1} → z_{t−2}) · beta(y_{s−1}) / (π r² N_L),
// with ρ's incoming direction the light walk's own (from y_{s−1} back toward y_{s−2}) and the
// shading-normal factor of kernels.h at z_{t−1}. Summed over every light vertex in the disc, this
// is a density estimate of the light arriving at z_{t−1}; consistent as r → 0.
//
// Only non-delta surfaces merge (the BSDF is evaluated there), and only with a light vertex on a
// surface facing the same way, so that light on the far side of a thin wall is not gathered.
#pragma once
#include <span>

#include "paths/connect.h"

namespace tripath {

// Merges light[s−1] (with light[0..s−1) its light prefix, s ≥ 2) with camera[t−1] (t ≥ 2):
// f/p of the merged path and its MIS weight among the enabled strategies (mis.h). The BSDF is
// camera[t−1]'s, as its subpath keeps it (vertex.h); no light vertex's is read.
Connection merge(const Scene& scene, std::span<const Vertex> light, int s, const SubpathView& camera, int t,
                 const MisContext& mis);

}  // namespace tripath
