// Whether the font is installed, asked of OpenImageIO, which searches the system font directories
// (/usr/share/fonts/...) by the faces' names as fontconfig does for Cairo.
#include "image/font.h"

#include <OpenImageIO/imagebufalgo.h>

#include <string>

#include "core/error.h"

namespace tripath {

void requireFont() {
    for (const char* face : {"DejaVuSans", "DejaVuSans-Bold"}) {
        const bool found = OIIO::ImageBufAlgo::text_size("Ag", 14, face).defined();
        OIIO::geterror();  // drained: OIIO complains at exit about errors nobody read
        if (!found)
            throw InputError(std::string("font ") + face +
                             " not found: install the fonts-dejavu-core package (scripts/install-deps.sh does)");
    }
}

}  // namespace tripath
