// The font every figure's text is set in: DejaVu Sans (Debian's fonts-dejavu-core, installed by
// scripts/install-deps.sh), which Cairo draws the comparison sheets, the charts and montages with.
#pragma once

namespace tripath {

// Throws InputError naming the missing font package unless its regular and bold faces are
// installed. Commands that end by drawing text call it first, so a missing font costs nothing but
// the error line.
void requireFont();

}  // namespace tripath
