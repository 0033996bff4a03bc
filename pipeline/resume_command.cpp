#include "pipeline/resume_command.h"

#include <algorithm>
#include <string_view>

namespace sl {

std::string shell_quote(const std::string& arg) {
    auto plain = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               std::string_view("_@%+=:,./-").find(c) != std::string_view::npos;
    };
    if (!arg.empty() && std::all_of(arg.begin(), arg.end(), plain)) return arg;
    std::string out = "'";
    for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

namespace {

// Outputs that need every section's bins in one run, which --resume refuses: the command that
// continues leaves them out (with their values), so that it is accepted.
bool needs_every_section(const std::string& arg, bool& takes_value) {
    static const std::pair<std::string_view, bool> kFlags[] = {
        {"--cube", true},   {"--cube-layout", true}, {"--hdf5", true},
        {"--phasor", true}, {"--gate", true},        {"--first-arrival", false},
        {"--first-arrival-threshold", true}};
    for (const auto& [flag, value] : kFlags) {
        if (arg == flag) {
            takes_value = value;
            return true;
        }
        if (value && arg.size() > flag.size() && arg.compare(0, flag.size(), flag) == 0 && arg[flag.size()] == '=') {
            takes_value = false;  // --flag=VALUE: one argument
            return true;
        }
    }
    return false;
}

std::vector<std::string> resumable(const std::vector<std::string>& argv) {
    std::vector<std::string> kept;
    bool after_dashes = false;
    for (size_t i = 0; i < argv.size(); ++i) {
        bool takes_value = false;
        if (!after_dashes && needs_every_section(argv[i], takes_value)) {
            if (takes_value) ++i;
            continue;
        }
        after_dashes |= argv[i] == "--";
        kept.push_back(argv[i]);
    }
    return kept;
}

}  // namespace

std::string resume_command(const std::vector<std::string>& given) {
    const std::vector<std::string> argv = resumable(given);
    std::string out;
    bool has_resume = false, after_dashes = false;
    for (const std::string& a : argv) {
        has_resume |= !after_dashes && a == "--resume";
        after_dashes |= a == "--";
        out += (out.empty() ? "" : " ") + shell_quote(a);
    }
    if (!has_resume) {
        // Options after "--" would be taken for file names: put --resume before it.
        auto it = std::find(argv.begin(), argv.end(), std::string("--"));
        if (it == argv.end()) return out + " --resume";
        std::string head;
        for (auto a = argv.begin(); a != argv.end(); ++a) {
            if (a == it) head += " --resume";
            head += (head.empty() ? "" : " ") + shell_quote(*a);
        }
        return head;
    }
    return out;
}

}  // namespace sl
