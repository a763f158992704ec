// A checkpoint's file: the state a render needs to go on exactly where it was cut. It holds the
// settings that must match to continue (as EXR metadata pairs), the pass counts, and the film's
// exact totals (film.h) word for word, so that a resumed --spp render equals the uninterrupted one
// bit for bit: totals add exactly, and checkpoints are taken at round boundaries, where every
// canonical block before nextPass is finished (render.h). It also holds the method's state
// (RenderResult::methodState), taken between passes: for mlt every Markov chain's
// (integrators/metropolis_render.h), so that each chain goes on where it stopped; for auto its
// moments and plans (integrators/auto.cpp), so that it chooses as the uninterrupted render would. The command line writes one beside its EXR and resumes from it
// (apps/checkpoint.h).
//
// Format: the line "tripath-checkpoint 3", then "key=value" lines (the settings, then passes,
// next-pass, seconds, dropped-samples, guarded-weights, values, chain-run, state-bytes and
// checksum), a blank line, the totals as little-endian 64-bit words, then the method's state
// (state-bytes bytes). The checksum is the 64-bit FNV-1a, in 16 hex digits, of the other header
// lines after the first and of everything after the blank line. Written to a temporary file and
// renamed over the target, so a job killed at any moment leaves the previous checkpoint whole.
#pragma once
#include <optional>
#include <string>

#include "image/image.h"
#include "integrators/render.h"

namespace tripath {

void writeCheckpoint(const std::string& path, const Metadata& settings, const RenderResult& r);

// The render saved at `path`, into a film of that size and those layers; nullopt if
// there is no such file. Throws InputError (one line naming the file) if it is not a regular file
// (a FIFO would block), not a checkpoint or of another format version, was made with other
// settings (naming the first that differs; of the scene, the first file whose content differs),
// has a header number that is not entirely a number in its range (next-pass at most
// kMaxFirstPass, seconds finite, from 0 to 1e9), a size other than its header gives, or contents
// that fail its checksum.
std::optional<RenderResult> readCheckpoint(const std::string& path, const Metadata& settings, int width, int height,
                                           const FilmLayers& layers);

}  // namespace tripath
