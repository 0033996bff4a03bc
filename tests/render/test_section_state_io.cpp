// The checkpoint format is full-image and pixel-ordered, whatever the buffer's tiling in
// memory: read back here byte by byte from the documented layout (not through the loader), so
// another process layout (ranks owning shares of the pixels) can rely on it. And a save/load
// round trip restores every bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <random>

#include "foundation/errors.h"
#include "tests/render/section_layout_fixture.h"
#include "stages/render/section_state_io.h"
#include "tests/common/temp_dir.h"

namespace sl {
namespace {

using test::whole_layout;

// 300 x 250 pixels: not a whole number of 16-pixel tiles, more than one write chunk.
constexpr int kW = 300, kH = 250, kFrames = 2;

std::unique_ptr<SectionBuffer> random_buffer(bool ambient) {
    auto b = std::make_unique<SectionBuffer>(size_t(kW) * kH, whole_layout(kFrames), 0.01f, ambient);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0, 1);
    for (auto& v : b->radius2) v = u(rng) * 1e-4;
    for (auto& v : b->photon_count) v = u(rng) * 1000;
    for (auto& v : b->accum) v = u(rng);
    for (auto& v : b->ambient) v = u(rng);
    // The last tile's padding pixels are never rendered into (and not saved): zero, as in a render.
    for (size_t p = size_t(kW) * kH; p < SectionBuffer::padded(size_t(kW) * kH); ++p)
        for (int s = 0; s < b->slots; ++s) std::fill(b->slot(p, s), b->slot(p, s) + 3, 0.0f);
    b->passes_done = 17;
    b->max_radius = 0.0123;
    b->volume_radius2 = 4.5e-5;
    return b;
}

SectionStateId id_of() {
    SectionStateId id;
    id.program_version = "9.9.9";
    id.fingerprint = "0123456789abcdef";
    id.section = 0, id.sections = 1, id.passes_target = 64, id.width = kW, id.height = kH;
    return id;
}

template <class T>
T at(const std::vector<char>& bytes, size_t offset) {
    T v;
    std::memcpy(&v, bytes.data() + offset, sizeof v);
    return v;
}

TEST(SectionStateIo, FileIsPixelOrderedAsDocumented) {
    test::TempDir dir("sl_state_io");
    auto b = random_buffer(true);
    const std::string path = dir.file("s.ckpt");
    const uint64_t bytes = save_section_state(path, *b, id_of(), false);
    std::ifstream f(path, std::ios::binary);
    std::vector<char> file{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
    ASSERT_EQ(file.size(), bytes);
    const size_t pixels = size_t(kW) * kH, slots = size_t(b->slots);
    ASSERT_EQ(bytes, kSectionStateHeaderBytes + pixels * (16 + 12 + slots * 12));
    EXPECT_EQ(std::string(file.data(), 8), "SLCHKPT\n");
    const size_t radius = kSectionStateHeaderBytes, count = radius + pixels * 8, ambient = count + pixels * 8,
                 buckets = ambient + pixels * 12;
    for (size_t p : {size_t(0), size_t(15), size_t(16), pixels / 2 + 3, size_t(70000), pixels - 1}) {
        EXPECT_EQ(at<double>(file, radius + p * 8), b->radius2[p]) << p;
        EXPECT_EQ(at<double>(file, count + p * 8), b->photon_count[p]) << p;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(at<float>(file, ambient + (p * 3 + c) * 4), b->ambient[p * 3 + c]);
        for (size_t s = 0; s < slots; ++s)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(at<float>(file, buckets + ((p * slots + s) * 3 + c) * 4), b->slot(p, int(s))[c]) << p << ' ' << s;
    }
}

TEST(SectionStateIo, RoundTripRestoresEveryBit) {
    test::TempDir dir("sl_state_io");
    for (bool ambient : {false, true}) {
        auto b = random_buffer(ambient);
        const std::string path = dir.file("s.ckpt");
        save_section_state(path, *b, id_of(), true);
        SectionStateInfo info;
        auto r = load_section_state(path, id_of(), whole_layout(kFrames), ambient, &info);
        EXPECT_TRUE(info.finished);
        EXPECT_EQ(info.passes_done, 17);
        EXPECT_EQ(r->radius2, b->radius2);
        EXPECT_EQ(r->photon_count, b->photon_count);
        EXPECT_EQ(r->accum, b->accum);
        EXPECT_EQ(r->ambient, b->ambient);
        EXPECT_EQ(r->passes_done, b->passes_done);
        EXPECT_EQ(r->max_radius, b->max_radius);
        EXPECT_EQ(r->volume_radius2, b->volume_radius2);
        // A checkpoint that does not match is refused, not trusted.
        SectionStateId other = id_of();
        other.section = 1, other.sections = 2;
        EXPECT_THROW(load_section_state(path, other, whole_layout(kFrames), ambient), InputError);
        EXPECT_THROW(load_section_state(path, id_of(), whole_layout(kFrames + 1), ambient), InputError);
        EXPECT_THROW(load_section_state(path, id_of(), whole_layout(kFrames), !ambient), InputError);
    }
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"s.ckpt"}) << "no temporary file left";
}

}  // namespace
}  // namespace sl
