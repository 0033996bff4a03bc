#include "pipeline/distributed/rank_start.h"

#include "foundation/message_lines.h"

#include <cstdio>
#include <cstring>

namespace sl {

int agree_to_start(RankExchange& ex, int status, const std::string& error) {
    std::string mine(sizeof(int), '\0');
    std::memcpy(mine.data(), &status, sizeof(int));
    if (status != 0) mine += error;
    std::vector<char> all;
    std::vector<uint64_t> counts;
    ex.gather(Channel::Frames, mine.data(), mine.size(), all, counts);
    if (ex.rank() == 0) {
        const char* at = all.data();
        for (uint64_t n : counts) {
            int s = 0;
            std::memcpy(&s, at, sizeof(int));
            if (s != 0) {
                std::fprintf(stderr, "%s\n", message_line("error: ", std::string(at + sizeof(int), n - sizeof(int))).c_str());
                break;
            }
            at += n;
        }
    }
    return ex.max(Channel::Frames, status);
}

}  // namespace sl
