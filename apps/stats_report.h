// The report `--stats` prints after a render: what it did and where its time went.
#pragma once
#include <cstdint>
#include <string>

#include "integrators/render.h"

namespace tripath::app {

// Every event counter in total, per camera sample (passes × pixels) and per second of the render;
// the rays of both kinds per second; the render's memory estimate by part beside the process's
// peak resident memory so far; auto's plans (planReport); and, if the phases were sampled, each
// one's share of the CPU time spent in them, with its sampling error. Several lines, each ending
// in a newline.
std::string statsReport(const RenderResult& r, uint64_t pixels);

// auto's plan of each stretch of passes and its candidates' estimates at the last choice; empty
// for the other methods.
std::string planReport(const PlanReport& plans);

}  // namespace tripath::app
