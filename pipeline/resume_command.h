#pragma once
// The exact command that continues an interrupted render: the command line as given, quoted
// for a POSIX shell, with --resume added if it is not there already.
#include <string>
#include <vector>

namespace sl {

std::string shell_quote(const std::string& arg);
std::string resume_command(const std::vector<std::string>& argv);

}  // namespace sl
