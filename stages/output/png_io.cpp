#include "stages/output/png_io.h"

#include <OpenImageIO/imageio.h>

#include <mutex>

#include "core/errors.h"
#include "stages/output/atomic_file.h"

namespace sl {

void write_png(const std::string& path, int w, int h, const uint8_t* rgb8) {
    // OIIO's own thread pool would compete with the renderer's TBB workers for the same cores.
    static std::once_flag once;
    std::call_once(once, [] { OIIO::attribute("threads", 1); });

    auto fail = [&](const std::string& why) {
        return RuntimeFailure(one_line("cannot write PNG '" + path + "': " + why));
    };
    if (w <= 0 || h <= 0) throw fail("empty image");

    const std::string temp = temp_sibling(path);
    // The temporary name has no .png extension, so the format is named explicitly.
    auto out = OIIO::ImageOutput::create("png");
    if (!out) throw fail(OIIO::geterror());
    const OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    const bool ok = out->open(temp, spec) && out->write_image(OIIO::TypeDesc::UINT8, rgb8) &&
                    out->close();
    if (!ok) {
        const std::string why = out->geterror();
        out.reset();
        discard_file(temp);
        throw fail(why);
    }
    out.reset();
    commit_file(temp, path);
}

}  // namespace sl
