// libFuzzer target: any bytes as a scene file and as a command line. Bad input must end in an
// InputError (one clear message), never a crash, a hang, or another exception.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "foundation/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string text(reinterpret_cast<const char*>(data), size);
    try {
        sl::SceneDesc scene = sl::parse_scene_text(text, "fuzz.json", "/nonexistent-dir");
        sl::RenderOverrides o;
        o.frames = 3;
        sl::apply_overrides(scene, o);
    } catch (const sl::InputError&) {
    }
    // The same bytes, split at NULs and spaces, as a command line.
    std::vector<std::string> words{"slowlight"};
    std::string cur;
    for (char c : text) {
        if (c == '\0' || c == ' ') {
            words.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    words.push_back(cur);
    std::vector<const char*> argv;
    for (auto& w : words) argv.push_back(w.c_str());
    try {
        sl::parse_command_line(static_cast<int>(argv.size()), argv.data());
    } catch (const sl::InputError&) {
    }
    return 0;
}
