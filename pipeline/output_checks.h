#pragma once
// Every output of a run, checked before anything is rendered: none may be one of the run's
// inputs (scene, meshes, and whatever importers read) or another output, and each must be
// writable. A run that would clobber a file or fail only at its end is refused at once, with
// one `error:` line naming the flag and path (exit status 2). Temporaries left in the output
// folders by earlier runs that were killed are removed on the way.
#include <string>
#include <vector>

namespace sl {

struct OutputRequest {
    std::string flag;  // "-o", "--stats", "--cube", "--exr-dir", "--png-dir", ...
    std::string path;
    bool directory = false;  // a folder the run writes files into
    // For a folder: the names the run writes there (frame_NNNN.exr ...), as a regular
    // expression over the file name; an input there with such a name would be overwritten.
    std::string names;
};

// The outputs a command line asks for (-o "-" is stdout and not a file).
struct RunOptions;
std::vector<OutputRequest> outputs_of(const RunOptions& o);

// Throws InputError on the first collision or unwritable output.
void check_outputs(const std::vector<OutputRequest>& outputs, const std::vector<std::string>& inputs);

}  // namespace sl
