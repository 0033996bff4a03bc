// The "may use" table of docs/architecture.md holds for every #include of the rooms' files.
//
// The table: a row per room; the first cell names the room's folders (`pipeline/`, ...), the
// "may use" cell the project headers it may include besides its own (a folder ending in `/`, or
// one file), the "may use libraries" cell the third-party headers it may include (each a start
// of the include path: `tbb/`, `mpi.h`). Standard and system headers are not checked; the
// third-party ones are recognised by kLibraries below.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "tests/docs/doc_text.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

// The starts of the third-party headers the project may include.
const char* const kLibraries[] = {"tbb/",   "oneapi/",      "nlohmann/",    "embree3/",        "embree4/",
                                  "OpenEXR/", "Imath/",     "libav",        "libsw",           "mpi.h",
                                  "OpenImageIO/", "tiny_gltf.h", "tiny_obj_loader.h", "xxhash.h", "stb_",
                                  "hdf5.h", "pybind11/", "Python.h"};

// The source tree's folders that are no room: no rule applies to them.
const char* const kNotRooms[] = {"tests", "bench", "fuzz", "docs", "samples", "scripts"};

struct Room {
    std::vector<std::string> folders;      // "pipeline/", "pipeline/distributed/"
    std::vector<std::string> may_use;      // "core/", "stages/render/rank_exchange.h"
    std::vector<std::string> libraries;    // "tbb/", "mpi.h"
};

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::vector<Room> rooms_in_doc(const std::string& text, std::string& problem) {
    std::vector<Room> rooms;
    int may_use = -1, libraries = -1;
    bool in_table = false;
    for (const std::string& line : test::lines_of(text)) {
        if (!test::is_table_row(line)) { if (in_table && !rooms.empty()) break; in_table = false; continue; }
        const std::vector<std::string> cells = test::table_cells(line);
        if (!in_table) {
            if (cells.empty() || cells[0] != "room") continue;
            for (size_t i = 0; i < cells.size(); ++i) {
                if (cells[i] == "may use") may_use = static_cast<int>(i);
                if (cells[i] == "may use libraries") libraries = static_cast<int>(i);
            }
            in_table = true;
            continue;
        }
        if (test::is_separator_row(line)) continue;
        if (may_use < 0 || libraries < 0 || static_cast<int>(cells.size()) <= std::max(may_use, libraries)) {
            problem = "the room table needs the columns \"may use\" and \"may use libraries\" in every row: " + line;
            return {};
        }
        Room r;
        r.folders = test::backticked(cells[0]);
        r.may_use = test::backticked(cells[static_cast<size_t>(may_use)]);
        r.libraries = test::backticked(cells[static_cast<size_t>(libraries)]);
        rooms.push_back(r);
    }
    if (rooms.empty()) problem = "no table with a \"room\" column";
    return rooms;
}

// The room a file belongs to: the one with the longest folder the file is in.
const Room* room_of(const std::vector<Room>& rooms, const std::string& file) {
    const Room* best = nullptr;
    size_t best_len = 0;
    for (const Room& r : rooms)
        for (const std::string& f : r.folders)
            if (starts_with(file, f) && f.size() > best_len) best = &r, best_len = f.size();
    return best;
}

bool allowed_project(const Room& r, const std::string& header) {
    for (const std::string& f : r.folders)
        if (starts_with(header, f)) return true;
    for (const std::string& u : r.may_use)
        if (u.back() == '/' ? starts_with(header, u) : header == u) return true;
    return false;
}

bool is_library(const std::string& header) {
    for (const char* l : kLibraries)
        if (starts_with(header, l)) return true;
    return false;
}

bool allowed_library(const Room& r, const std::string& header) {
    for (const std::string& l : r.libraries)
        if (starts_with(header, l)) return true;
    return false;
}

// Every C++ file of the source tree outside kNotRooms, as a path relative to it.
std::vector<std::string> project_files(const fs::path& root) {
    std::vector<std::string> files;
    for (const auto& top : fs::directory_iterator(root)) {
        const std::string name = top.path().filename().string();
        if (!top.is_directory() || name.empty() || name[0] == '.' || starts_with(name, "build")) continue;
        if (std::find(std::begin(kNotRooms), std::end(kNotRooms), name) != std::end(kNotRooms)) continue;
        for (const auto& e : fs::recursive_directory_iterator(top.path())) {
            const std::string ext = e.path().extension().string();
            if (e.is_regular_file() && (ext == ".h" || ext == ".hpp" || ext == ".cpp" || ext == ".cc"))
                files.push_back(fs::relative(e.path(), root).generic_string());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

struct Breach {
    std::string file, include, why;
};

// Every include of every room's file that its row does not allow.
std::vector<Breach> breaches(const std::vector<Room>& rooms, const fs::path& root, size_t& includes_seen) {
    static const std::regex include(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
    std::vector<Breach> out;
    for (const std::string& file : project_files(root)) {
        const Room* room = room_of(rooms, file);
        if (!room) {
            out.push_back({file, "", "the file is in no room of the table"});
            continue;
        }
        for (const std::string& line : test::lines_of(test::read_text((root / file).string()))) {
            std::smatch m;
            if (!std::regex_search(line, m, include)) continue;
            ++includes_seen;
            const std::string header = m[2];
            const bool quoted = m[1] == "\"";
            if (quoted || fs::exists(root / header)) {
                std::string project = header;
                if (!fs::exists(root / header)) {  // relative to the including file
                    const fs::path beside = (root / file).parent_path() / header;
                    if (fs::exists(beside))
                        project = fs::relative(beside, root).lexically_normal().generic_string();
                    else if (is_library(header)) project.clear();
                    else { out.push_back({file, header, "names no file of the source tree"}); continue; }
                }
                if (!project.empty()) {
                    if (!allowed_project(*room, project))
                        out.push_back({file, header, "its room may not use " + project});
                    continue;
                }
            }
            if (is_library(header) && !allowed_library(*room, header))
                out.push_back({file, header, "a library its room's \"may use libraries\" does not name"});
        }
    }
    return out;
}

const std::string kDoc = "docs/architecture.md";

TEST(ArchitectureIncludes, EveryIncludeKeepsTheRoomTable) {
    std::string problem;
    const std::vector<Room> rooms = rooms_in_doc(test::read_text(test::source_path(kDoc)), problem);
    ASSERT_FALSE(rooms.empty()) << kDoc << ": " << problem;
    size_t seen = 0;
    for (const Breach& b : breaches(rooms, test::source_dir(), seen))
        ADD_FAILURE() << b.file << (b.include.empty() ? "" : ": #include " + b.include) << ": " << b.why
                      << " (" << kDoc << ", the room table)";
    EXPECT_GT(seen, 500u);  // the files were found and read
}

TEST(ArchitectureIncludes, EveryRoomOfTheTableExists) {
    std::string problem;
    const std::vector<Room> rooms = rooms_in_doc(test::read_text(test::source_path(kDoc)), problem);
    ASSERT_FALSE(rooms.empty()) << kDoc << ": " << problem;
    for (const Room& r : rooms) {
        EXPECT_FALSE(r.folders.empty()) << kDoc << ": a row of the room table names no folder";
        for (const std::string& f : r.folders)
            EXPECT_TRUE(fs::is_directory(test::source_path(f))) << kDoc << ": room " << f << " does not exist";
        for (const std::string& u : r.may_use)
            EXPECT_TRUE(fs::exists(test::source_path(u))) << kDoc << ": " << u << " (may use) does not exist";
        for (const std::string& l : r.libraries)
            EXPECT_TRUE(is_library(l)) << kDoc << ": `" << l << "` (may use libraries) is not the start of a known "
                                       << "library's headers (kLibraries in this test)";
    }
}

// The checker itself, on a table and a tree of its own: it names the file and the include.
TEST(ArchitectureIncludes, ABreachIsNamedWithItsFileAndInclude) {
    const fs::path root = fs::temp_directory_path() / ("sl_arch_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "low");
    fs::create_directories(root / "high");
    auto write = [&](const std::string& path, const std::string& text) { std::ofstream(root / path) << text; };
    write("low/a.h", "#pragma once\n#include <vector>\n");
    write("high/b.cpp", "#include \"low/a.h\"\n#include <tbb/task_group.h>\n");
    write("low/c.cpp", "#include \"high/b.h\"\n#include \"a.h\"\n#include <nlohmann/json.hpp>\n");
    write("high/b.h", "#pragma once\n");
    std::string problem;
    const std::vector<Room> rooms = rooms_in_doc(
        "| room | its job | may use | may use libraries |\n|---|---|---|---|\n"
        "| `high/` | up | `low/` | oneTBB (`tbb/`) |\n| `low/` | down | nothing | none |\n", problem);
    ASSERT_EQ(rooms.size(), 2u) << problem;
    size_t seen = 0;
    const std::vector<Breach> b = breaches(rooms, root, seen);
    fs::remove_all(root);
    ASSERT_EQ(b.size(), 2u);
    EXPECT_EQ(b[0].file + " " + b[0].include, "low/c.cpp high/b.h");
    EXPECT_EQ(b[1].file + " " + b[1].include, "low/c.cpp nlohmann/json.hpp");
    EXPECT_EQ(seen, 6u);
}

}  // namespace
}  // namespace sl
