#include "pipeline/distributed/resume_on_ranks.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>

#include "foundation/errors.h"
#include "pipeline/distributed/rank_start.h"

namespace sl {

int share_resume_plan(RankExchange& ex, const std::function<void(std::vector<SectionStart>&, std::vector<bool>&)>& judge,
                      std::vector<SectionStart>& starts, std::vector<bool>& on_disk) {
    int status = 0;
    std::string error;
    if (ex.rank() == 0) {
        try {
            judge(starts, on_disk);
        } catch (const InputError& e) {
            status = 2, error = e.what();
        } catch (const std::exception& e) {
            status = 1, error = e.what();
        }
    }
    status = agree_to_start(ex, status, error);
    if (status != 0) return status;
    // Per section: from a checkpoint, finished in it, passes done, frames on disk.
    struct Entry {
        int32_t passes_done;
        uint8_t from_checkpoint, finished, on_disk, unused;
    };
    std::vector<char> bytes;
    if (ex.rank() == 0) {
        const size_t n = std::max(starts.size(), on_disk.size());
        bytes.resize(n * sizeof(Entry));
        for (size_t s = 0; s < n; ++s) {
            Entry e{};
            if (s < starts.size()) {
                e.passes_done = starts[s].passes_done;
                e.from_checkpoint = starts[s].from_checkpoint;
                e.finished = starts[s].finished;
            }
            e.on_disk = s < on_disk.size() && on_disk[s];
            std::memcpy(bytes.data() + s * sizeof(Entry), &e, sizeof e);
        }
    }
    ex.broadcast(Channel::Frames, bytes);
    if (ex.rank() == 0) return 0;
    const size_t n = bytes.size() / sizeof(Entry);
    starts.assign(n, SectionStart{});
    on_disk.assign(n, false);
    for (size_t s = 0; s < n; ++s) {
        Entry e;
        std::memcpy(&e, bytes.data() + s * sizeof(Entry), sizeof e);
        starts[s].passes_done = e.passes_done;
        starts[s].from_checkpoint = e.from_checkpoint != 0;
        starts[s].finished = e.finished != 0;
        on_disk[s] = e.on_disk != 0;
    }
    return 0;
}

}  // namespace sl
