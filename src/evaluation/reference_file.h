// Reference EXRs as `tripath reference` writes them and `tripath compare` reads them: the image
// plus the tripath:* metadata saying how it was rendered, and the checks that a reference fits
// the render it is used with.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/rng.h"
#include "image/image.h"

namespace tripath::evaluation {

struct ReferenceFile {
    std::string path;
    Image image;
    Metadata meta;

    std::optional<std::string> value(const std::string& key) const;
    // tripath:spp and tripath:seconds; 0 when absent (an EXR from another renderer). Throw
    // InputError for anything but a whole number of passes up to INT_MAX and a finite, non-negative
    // number of seconds.
    int spp() const;
    double seconds() const;
    // The value of `key` as a whole number from 0 to `max`, or `absent` when the file lacks the key;
    // throws InputError, naming the file and the key, for any other text ("-5", "12x", "abc").
    uint64_t wholeNumber(const std::string& key, uint64_t max, uint64_t absent) const;
    // "bdpt, 4096 spp, 300 s" or "external reference" when there is no metadata to tell.
    std::string description() const;
};

// The random streams its samples came from (tripath:streams): Reference for "reference",
// CameraSample for "render" and for files without the key (`tripath render` output, references
// written before the key existed, other renderers' EXRs). Throws InputError for any other value.
StreamDomain streamDomain(const ReferenceFile& ref);

// Throws InputError (one line naming the file) if it is missing or not an EXR, or if a number its
// metadata records (tripath:spp, seconds, next-pass, dropped-samples, seed) is not entirely a
// number in its range (wholeNumber; next-pass at most kMaxFirstPass, integrators/render.h).
ReferenceFile readReference(const std::string& path);

// Throws InputError unless the reference is width x height.
void requireSize(const ReferenceFile& ref, int width, int height);
// Throws InputError naming the first key whose value in the reference differs from the expected
// one (tripath:scene-files by content: the first file that differs, scene_identity.h). Keys the
// reference lacks are skipped when `allowMissing`, an error otherwise.
void requireSettings(const ReferenceFile& ref, const std::vector<std::pair<std::string, std::string>>& expected,
                     bool allowMissing);

// Replaces the value of `key`, or appends it.
void setMetadata(Metadata& meta, const std::string& key, const std::string& value);

}  // namespace tripath::evaluation
