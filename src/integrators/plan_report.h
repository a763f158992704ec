// What auto chose (integrators/auto.cpp), as a render's result carries it to the output: the plan
// of each stretch of passes, each candidate's estimates at the last choice, and the classes of
// strategies each tile ran in the last stretch — in the EXR as text (tripath:auto-plans,
// tripath:auto-tiles) and as one channel per class, a value per pixel, so that a viewer lays the
// choice over the image.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "image/image.h"

namespace tripath {

// The classes of strategies a tile runs (pass_plan.h), a bit each: the camera walk's emitter hits
// and next-event estimates, the connections, light tracing's joins to the sensor, the merges.
enum ClassBit : uint8_t { kCameraWalkClass = 1, kConnectClass = 2, kTraceClass = 4, kMergeClass = 8 };

// The classes' names as the output shows them: "pt" for the camera walk's alone, else the names of
// the classes joined by "+", e.g. "pt+connect+merge", "trace".
std::string classesName(uint8_t classes);

// A candidate's estimates at the last choice, as if every tile ran it (plan_choice.h): its
// relative variance per pass, its cost per pass in traced rays, and whether it cannot sample a
// path some pass found light on.
struct PlanEstimate {
    std::string plan;
    double relativeVariance = 0, cost = 0;
    bool uncovered = false;
};

struct PlanReport {
    std::vector<std::pair<uint64_t, std::string>> stretches;  // (offset of its first pass, its plans)
    std::vector<PlanEstimate> candidates;                      // the choice itself last
    std::vector<uint8_t> tiles;  // the ClassBits each tile runs in the last stretch, in row order
    int tilesAcross = 0;         // tiles in a row
    int tileSize = 0;            // pixels on a tile's side
};

// Per pixel of a width × height image, 1 where the pixel's tile runs the class in the last stretch
// and 0 elsewhere: the channels auto.pt, auto.connect, auto.trace and auto.merge. None for a
// report without tiles (every method but auto).
std::vector<ExrChannel> classChannels(const PlanReport& plans, int width, int height);

}  // namespace tripath
