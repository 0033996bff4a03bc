// Every flag that `slowlight --help` and `slowlight COMMAND --help` print is documented in
// README.md or docs/*.md. The help text is usage_text(), which pipeline/cli.cpp prints.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "config/command_line.h"
#include "tests/docs/doc_text.h"

namespace sl {
namespace {

// The flags a help text offers: those its option lines begin with ("  -o, --output PATH ...",
// "      --frames N ...") and those on its command lines ("  slowlight --help, --version").
std::set<std::string> flags_in_help(const std::string& help) {
    static const std::regex option_line(R"(^\s+(-[A-Za-z])?(, )?(--[a-z][a-z0-9-]*)?)");
    static const std::regex flag(R"((^|[\s,\[])(--?[a-z][a-z0-9-]*))");
    std::set<std::string> flags;
    for (const std::string& line : test::lines_of(help)) {
        const std::string t = test::trim(line);
        std::smatch m;
        if (t.rfind("slowlight ", 0) == 0 && line.rfind("  ", 0) == 0) {  // a command line
            for (auto it = std::sregex_iterator(line.begin(), line.end(), flag); it != std::sregex_iterator(); ++it)
                flags.insert((*it)[2]);
        } else if (t.rfind("-", 0) == 0 && std::regex_search(line, m, option_line)) {
            if (m[1].matched) flags.insert(m[1]);
            if (m[3].matched) flags.insert(m[3]);
        }
    }
    return flags;
}

// Whether `flag` is written in `text` as a word of its own (--exposure-follow is not --exposure).
bool mentions(const std::string& text, const std::string& flag) {
    auto word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; };
    for (size_t at = text.find(flag); at != std::string::npos; at = text.find(flag, at + 1)) {
        const bool starts = at == 0 || !word_char(text[at - 1]);
        const size_t end = at + flag.size();
        const bool ends = end == text.size() || !word_char(text[end]);
        if (starts && ends) return true;
    }
    return false;
}

std::string all_docs() {
    std::string text = test::read_text(test::source_path("README.md"));
    for (const auto& e : std::filesystem::directory_iterator(test::source_path("docs")))
        if (e.path().extension() == ".md") text += "\n" + test::read_text(e.path().string());
    return text;
}

TEST(DocsMatchFlags, EveryFlagOfEveryHelpIsInTheReadmeOrTheDocs) {
    const std::string docs = all_docs();
    ASSERT_FALSE(docs.empty());
    std::vector<std::string> topics{""};
    for (std::string_view t : help_topics()) topics.emplace_back(t);
    size_t checked = 0;
    for (const std::string& topic : topics) {
        const std::string help = usage_text(topic);
        const std::set<std::string> flags = flags_in_help(help);
        EXPECT_FALSE(flags.empty()) << "no flags found in `slowlight " << topic << " --help`";
        for (const std::string& f : flags) {
            ++checked;
            EXPECT_TRUE(mentions(docs, f)) << "`slowlight " << (topic.empty() ? "" : topic + " ") << "--help` offers "
                                           << f << ", which neither README.md nor docs/*.md mentions";
        }
    }
    EXPECT_GT(checked, 30u);  // the extraction still finds the option lines
}

// The extraction itself: it must see the flags of an option line and of the command lines, and
// not take an option's value for a flag.
TEST(DocsMatchFlags, FlagsAreFoundInOptionAndCommandLines) {
    const std::set<std::string> f = flags_in_help(
        "Commands:\n  slowlight --help, --version\n\nOptions (given as --opt VALUE):\n"
        "  -o, --output PATH       write\n      --max-bucket-memory SIZE  the same\n");
    EXPECT_EQ(f, (std::set<std::string>{"--help", "--version", "-o", "--output", "--max-bucket-memory"}));
    EXPECT_TRUE(mentions("use `--exposure X`", "--exposure"));
    EXPECT_FALSE(mentions("use --exposure-follow", "--exposure"));
}

}  // namespace
}  // namespace sl
