// Textures held in the smallest form that keeps their values (8-bit images as bytes, the rest as
// half floats), the half-float conversion against Imath's, and the import budget that refuses a
// texture from its header before any texel is decoded.
#include <gtest/gtest.h>

#define IMATH_HALF_NO_LOOKUP_TABLE  // Imath's conversion in the header alone: a second path
#include <Imath/half.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "core/import/resolve_imports.h"
#include "core/texture_load.h"
#include "foundation/errors.h"
#include "foundation/half_float.h"
#include "stages/output/exr_io.h"
#include "stages/output/png_io.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/pipeline/run_program.h"

namespace sl::test {
namespace {

TEST(HalfFloat, EveryHalfSurvivesTheRoundTripAndMatchesImath) {
    for (uint32_t h = 0; h < 65536; ++h) {
        const uint16_t bits = static_cast<uint16_t>(h);
        const float f = half_to_float(bits);
        Imath::half ref;
        ref.setBits(bits);
        if (std::isnan(static_cast<float>(ref))) {
            EXPECT_TRUE(std::isnan(f)) << h;
            continue;
        }
        ASSERT_EQ(f, static_cast<float>(ref)) << h;
        ASSERT_EQ(float_to_half(f), bits) << h;
    }
}

TEST(HalfFloat, RoundsFloatsToNearestEvenAsImathDoes) {
    // Every 97th float bit pattern over the positive and negative finite range, the ties between
    // halves, subnormals and the overflow edge included.
    for (uint64_t x = 0; x < 0x7f800000ull; x += 97) {
        for (uint32_t sign : {0u, 0x80000000u}) {
            const uint32_t bits = static_cast<uint32_t>(x) | sign;
            float f;
            std::memcpy(&f, &bits, 4);
            ASSERT_EQ(float_to_half(f), Imath::half(f).bits()) << std::hexfloat << f;
        }
    }
    EXPECT_EQ(float_to_half(65504.0f), Imath::half(65504.0f).bits());
    EXPECT_EQ(float_to_half(65520.0f), Imath::half(65520.0f).bits());  // rounds to infinity
}

// sRGB byte to linear, written out here as the sRGB standard gives it.
double srgb_linear(int byte) {
    const double c = byte / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST(TextureStorage, EightBitImagesKeepFourBytesATexelAndTheirValues) {
    TempDir dir;
    const int w = 5, h = 3;
    std::vector<uint8_t> rgb(w * h * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>((i * 37 + 11) % 256);
    write_png(dir.file("t.png"), w, h, rgb.data());
    for (bool srgb : {true, false}) {
        const auto tex = load_texture({dir.file("t.png"), nullptr, "", srgb});
        EXPECT_EQ(tex->format, srgb ? TexelFormat::Srgb8 : TexelFormat::Linear8);
        EXPECT_EQ(tex->bytes(), static_cast<uint64_t>(w * h * 4));
        double sum = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c) {
                    const int b = rgb[static_cast<size_t>((y * w + x) * 3 + c)];
                    const double want = srgb ? srgb_linear(b) : b / 255.0;
                    EXPECT_NEAR(tex->texel(x, y)[c], want, 1e-6) << x << ',' << y;
                    if (c == 0) sum += want;
                }
        EXPECT_NEAR(tex->mean.x, sum / (w * h), 1e-6);
    }
}

TEST(TextureStorage, FloatImagesBecomeHalvesWithTheirOutliersCounted) {
    TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> rgb = {0.1234f, 1.5f, 3000.25f,  1e6f, -2.0f, nan,
                                    1e-5f,   0.0f, 65504.0f,  7.0f, 8.0f,  9.0f};
    write_exr(dir.file("t.exr"), 2, 2, rgb.data());
    const auto tex = load_texture({dir.file("t.exr"), nullptr, "", true});  // floats: linear regardless
    EXPECT_EQ(tex->format, TexelFormat::Half);
    EXPECT_EQ(tex->bytes(), 2u * 2 * 6);
    EXPECT_EQ(tex->replaced, 2u);  // -2 and NaN
    EXPECT_EQ(tex->clamped, 1u);   // 1e6
    const std::vector<float> want = {0.1234f, 1.5f, 3000.25f, 65504.0f, 0, 0, 1e-5f, 0, 65504.0f, 7, 8, 9};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = want[static_cast<size_t>(i * 3 + c)];
            EXPECT_EQ(tex->texel(i % 2, i / 2)[c], static_cast<float>(Imath::half(v))) << i << ',' << c;
            EXPECT_NEAR(tex->texel(i % 2, i / 2)[c], v, std::fabs(v) * 1e-3 + 1e-7);
        }
}

// An OBJ whose one quad is drawn with `image`.
std::string textured_obj(TempDir& dir, const std::string& image) {
    ModelMesh m;
    m.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    m.quad({-0.2f, 1, -0.2f}, {0, 0, 0.4f}, {0.4f, 0, 0}, 1);
    write_obj(dir.file("m.obj"), "m.mtl", m, {{"floor", Vec3(0.5f), Vec3(0), image}, {"lamp", Vec3(0), Vec3(5)}});
    return dir.file("m.obj");
}

SceneDesc scene_of(const std::string& obj) {
    SceneDesc s;
    s.source = "scene.json";
    s.shapes.push_back(model_shape(obj));
    return s;
}

TEST(ImportBudget, RefusesATextureFromItsHeaderWithTheBytesItNeeds) {
    TempDir dir;
    std::vector<uint8_t> grey(512 * 512 * 3, 90);
    write_png(dir.file("big.png"), 512, 512, grey.data());
    SceneDesc s = scene_of(textured_obj(dir, "big.png"));
    try {
        resolve_imports(s, {300000, "--max-memory 292.97 KiB"});
        FAIL() << "a 1 MiB texture fitted in 293 KiB";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("big.png (512x512, 1.0 MiB)"), std::string::npos) << m;
        EXPECT_NE(m.find("more than --max-memory 292.97 KiB"), std::string::npos) << m;
        EXPECT_NE(m.find("nothing was decoded"), std::string::npos) << m;
    }
    EXPECT_TRUE(s.textures.empty());
    // With room for it, the same scene loads, and holds the bytes the header promised.
    SceneDesc t = scene_of(textured_obj(dir, "big.png"));
    resolve_imports(t, {2u << 20, "--max-memory 2 MiB"});
    ASSERT_EQ(t.textures.size(), 1u);
    EXPECT_EQ(texture_bytes(t), 512u * 512 * 4);
}

TEST(ImportBudget, TheCommandLineRefusesATextureBeyondMaxMemoryWithExitTwo) {
    TempDir dir;
    std::vector<uint8_t> grey(2048 * 2048 * 3, 200);
    write_png(dir.file("huge.png"), 2048, 2048, grey.data());  // 16 MiB as bytes, 48 MiB as floats
    const std::string obj = textured_obj(dir, "huge.png");
    ProgramResult r = run_program({"render", obj, "--max-memory", "12M", "--exr-dir", dir.file("out")});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("huge.png (2048x2048, 16.0 MiB)"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
}

}  // namespace
}  // namespace sl::test
