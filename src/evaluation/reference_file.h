// Reference EXRs as `tripath reference` writes them and `tripath compare` reads them: the image
// plus the tripath:* metadata saying how it was rendered, and the checks that a reference fits
// the render it is used with.
#pragma once
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
    // tripath:spp and tripath:seconds; 0 when absent (an EXR from another renderer).
    int spp() const;
    double seconds() const;
    // "bdpt, 4096 spp, 300 s" or "external reference" when there is no metadata to tell.
    std::string description() const;
};

// The random streams its samples came from (tripath:streams): Reference for "reference",
// CameraSample for "render" and for files without the key (`tripath render` output, references
// written before the key existed, other renderers' EXRs). Throws InputError for any other value.
StreamDomain streamDomain(const ReferenceFile& ref);

// Throws InputError (one line naming the file) if it is missing or not an EXR.
ReferenceFile readReference(const std::string& path);

// Throws InputError unless the reference is width x height.
void requireSize(const ReferenceFile& ref, int width, int height);
// Throws InputError naming the first key whose value in the reference differs from the expected
// one. Keys the reference lacks are skipped when `allowMissing`, an error otherwise.
void requireSettings(const ReferenceFile& ref, const std::vector<std::pair<std::string, std::string>>& expected,
                     bool allowMissing);

// Replaces the value of `key`, or appends it.
void setMetadata(Metadata& meta, const std::string& key, const std::string& value);

}  // namespace tripath::evaluation
