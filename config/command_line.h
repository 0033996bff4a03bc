#pragma once
// The command line:
//   slowlight render [SCENE.json] [options] | slowlight info SCENE.json [options]
//   slowlight retime CUBE.npy [options] | slowlight [COMMAND] --help | slowlight --version
// Options may come before or after the scene, as `--opt value` or `--opt=value`; a later
// option overrides an earlier one. Errors throw InputError "command line: <what>".
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "config/run_options.h"

namespace sl {

RunOptions parse_command_line(int argc, const char* const* argv);

// InputError when render or retime would write nothing at all (before any work starts).
void require_an_output(const RunOptions& options);

// The --help text: every command and option, one line each; with a topic ("render", "info",
// "retime"), that command's own help with only the options it uses.
std::string usage_text(const std::string& topic = "");

// The commands with a help of their own (`slowlight render --help`), the topics usage_text takes.
std::span<const std::string_view> help_topics();

// The commands, one line each: what `slowlight` alone prints after its error line.
std::string commands_text();

// A byte count such as "512M", "2G", "1.5GiB", "1024": K, M, G, T are binary multiples
// (1024), an optional trailing B or iB, any case. Nothing when malformed, zero or too large.
std::optional<uint64_t> parse_byte_size(std::string_view text);

}  // namespace sl
