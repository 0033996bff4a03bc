// slowlight: slow-motion videos of light, rendered by transient progressive photon mapping.
#include <malloc.h>

#include "pipeline/cli.h"

int main(int argc, char** argv) {
    // One malloc arena for every thread. Per-pass working sets (the photon map, frames on their
    // way out) are allocated by whichever TBB worker runs that stage; with glibc's per-thread
    // arenas the memory one thread freed could not serve another's next section, and the peak
    // grew by a photon map per arena. Nothing hot allocates, so one arena costs no speed.
    mallopt(M_ARENA_MAX, 1);
    // Blocks of 128 KiB and more (frames, photon maps, the encoder's pictures) come from mmap
    // and go back to the system when freed. glibc otherwise raises this threshold to the size
    // of the largest block freed so far, after which each frame's 3 MiB came from the heap and
    // the heap crept up, section after section, by the holes between them.
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
    return sl::run_cli(argc, argv);
}
