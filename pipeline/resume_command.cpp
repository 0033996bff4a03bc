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

std::string resume_command(const std::vector<std::string>& argv) {
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
