// slowlight: slow-motion videos of light, rendered by transient progressive photon mapping.
#include <malloc.h>

#include "pipeline/cli.h"

int main(int argc, char** argv) {
    // One malloc arena for every thread. Per-pass working sets (the photon map, frames on their
    // way out) are allocated by whichever TBB worker runs that stage; with glibc's per-thread
    // arenas the memory one thread freed could not serve another's next section, and the peak
    // grew by a photon map per arena. Nothing hot allocates, so one arena costs no speed.
    mallopt(M_ARENA_MAX, 1);
    return sl::run_cli(argc, argv);
}
