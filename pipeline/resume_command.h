#pragma once
// The exact command that continues an interrupted render: the command line as given, quoted
// for a POSIX shell, with --resume added if it is not there already, and without the outputs
// --resume refuses because they need every section in one run (--cube, --hdf5, the sensor
// images: docs/transient-outputs.md).
#include <string>
#include <vector>

namespace sl {

std::string shell_quote(const std::string& arg);
std::string resume_command(const std::vector<std::string>& argv);

}  // namespace sl
