#pragma once
namespace sl {
// Runs the program for a command line and returns its exit status (0, 1, 2 or 130), having
// printed exactly one `error:` line on stderr for a failure.
int run_cli(int argc, char** argv);
}  // namespace sl
