// The header walk that runs before OpenEXR opens a file we read back: valid frames pass with the
// same metadata OpenEXR reads, and every shape this program never writes is refused by name
// before the library could size a table from it.
#include "stages/output/exr_header_scan.h"

#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "foundation/errors.h"
#include "stages/output/exr_io.h"
#include "tests/common/temp_dir.h"

namespace {

std::vector<char> bytes_of(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), {}};
}

void put(const std::string& path, const std::vector<char>& b) {
    std::ofstream(path, std::ios::binary).write(b.data(), static_cast<std::streamsize>(b.size()));
}

// Offset of the value of attribute `name` in a file's header.
size_t value_at(const std::vector<char>& b, const std::string& name) {
    const std::string key = name + std::string(1, '\0');
    auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
    EXPECT_NE(it, b.end()) << name;
    size_t at = size_t(it - b.begin()) + key.size();
    while (b[at] != 0) ++at;  // the type name
    return at + 1 + 4;        // past its NUL and the size
}

std::string refusal(const std::string& path, sl::ExrSize want = {}) {
    try {
        sl::read_exr(path, want);
    } catch (const sl::RuntimeFailure& e) {
        return e.what();
    }
    return "";
}

struct Frame {
    sl::test::TempDir dir;
    std::string path = dir.file("f.exr");
    explicit Frame(int w = 8, int h = 6) {
        std::vector<float> rgb(size_t(w) * h * 3, 0.5f);
        sl::write_exr(path, w, h, rgb.data(), {{"slowlight:frame", "3"}, {"note", "x"}});
    }
};

}  // namespace

TEST(ExrHeaderScan, ValidFrameGivesWhatOpenExrReads) {
    Frame f;
    const sl::ExrHeaderInfo h = sl::scan_exr_header(f.path);
    const sl::ExrImage img = sl::read_exr(f.path, {8, 6});
    EXPECT_EQ(h.metadata, img.metadata);
    EXPECT_EQ(h.data_x1 - h.data_x0 + 1, img.width);
    EXPECT_EQ(h.data_y1 - h.data_y0 + 1, img.height);
    EXPECT_EQ(h.channels.size(), 3u);
    EXPECT_EQ(h.channels.at("G"), "float");
}

TEST(ExrHeaderScan, AnotherSizeThanTheRendersIsRefusedNamingBoth) {
    Frame f(4, 3);
    const std::string why = refusal(f.path, {8, 6});
    EXPECT_NE(why.find("4 x 3"), std::string::npos) << why;
    EXPECT_NE(why.find("8 x 6"), std::string::npos) << why;
}

// The window forged wide: OpenEXR would size line buffers from it on opening the file.
TEST(ExrHeaderScan, ForgedHugeWindowIsRefusedBeforeOpenExr) {
    Frame f;
    std::vector<char> b = bytes_of(f.path);
    for (const char* name : {"dataWindow", "displayWindow"}) {
        const int32_t box[4] = {0, 0, (1 << 24) - 1, 5};
        std::memcpy(&b[value_at(b, name)], box, 16);
    }
    put(f.path, b);
    EXPECT_NE(refusal(f.path).find("too large"), std::string::npos) << refusal(f.path);
    EXPECT_NE(refusal(f.path, {8, 6}).find("not this render's"), std::string::npos);
}

TEST(ExrHeaderScan, ExtraChannelIsRefused) {
    sl::test::TempDir dir;
    Imf::Header header(4, 4);
    for (const char* c : {"R", "G", "B", "Z"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    const std::string path = dir.file("rgbz.exr");
    { Imf::OutputFile out(path.c_str(), header); }  // header only: the pixels are never reached
    EXPECT_NE(refusal(path).find("channel 'Z'"), std::string::npos) << refusal(path);
}

TEST(ExrHeaderScan, TiledFileIsRefused) {
    sl::test::TempDir dir;
    Imf::Header header(4, 4);
    header.setTileDescription(Imf::TileDescription(2, 2));
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    const std::string path = dir.file("tiled.exr");
    { Imf::TiledOutputFile out(path.c_str(), header); }
    EXPECT_NE(refusal(path).find("tiled"), std::string::npos) << refusal(path);
}

TEST(ExrHeaderScan, AttributeTwiceOrPastTheEndIsRefused) {
    Frame f;
    std::vector<char> b = bytes_of(f.path);
    std::vector<char> twice = b;
    const std::string note = std::string("note") + '\0' + "string" + '\0';
    auto it = std::search(twice.begin(), twice.end(), note.begin(), note.end());
    ASSERT_NE(it, twice.end());
    const size_t at = size_t(it - twice.begin());
    // name, type, 4-byte size, the one-byte value "x": inserted again in front of itself
    std::vector<char> attr(twice.begin() + long(at), twice.begin() + long(at + note.size() + 4 + 1));
    twice.insert(twice.begin() + long(at), attr.begin(), attr.end());
    put(f.path, twice);
    EXPECT_NE(refusal(f.path).find("appears twice"), std::string::npos) << refusal(f.path);

    const int32_t huge = 1 << 30;
    std::memcpy(&b[value_at(b, "note") - 4], &huge, 4);
    put(f.path, b);
    EXPECT_NE(refusal(f.path).find("runs past"), std::string::npos) << refusal(f.path);
}
