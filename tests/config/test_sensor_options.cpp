// The sensor images' values on the command line: frequencies with their units, the gate's
// window, and the names the frequencies give the files.
#include <gtest/gtest.h>

#include "config/command_line.h"
#include "config/sensor_options.h"
#include "foundation/errors.h"

namespace sl {
namespace {

TEST(SensorOptions, FrequenciesCarryTheirUnits) {
    FrequencyList f = parse_frequencies("1.5GHz,40MHz,500khz,2e7Hz");
    ASSERT_TRUE(f.error.empty()) << f.error;
    ASSERT_EQ(f.hz.size(), 4u);
    EXPECT_DOUBLE_EQ(f.hz[0], 1.5e9);
    EXPECT_DOUBLE_EQ(f.hz[1], 4e7);
    EXPECT_DOUBLE_EQ(f.hz[2], 5e5);
    EXPECT_DOUBLE_EQ(f.hz[3], 2e7);
    EXPECT_EQ(frequency_label(f.hz[0]), "1500MHz");
    EXPECT_EQ(frequency_label(f.hz[2]), "0.5MHz");
    EXPECT_EQ(frequency_label(f.hz[3]), "20MHz");
    // A bare number, an empty item, zero, a negative, a repeat (20MHz = 0.02GHz) are refused.
    for (const char* bad : {"20", "20MHz,", "0MHz", "-5MHz", "20MHz,0.02GHz", "nanMHz", "MHz", "20 MHz"})
        EXPECT_FALSE(parse_frequencies(bad).error.empty()) << bad;
}

TEST(SensorOptions, TheGateIsAStartAndAWidthInNanoseconds) {
    GateWindow g = parse_gate("12.5:3");
    ASSERT_TRUE(g.error.empty()) << g.error;
    EXPECT_DOUBLE_EQ(g.start_ns, 12.5);
    EXPECT_DOUBLE_EQ(g.width_ns, 3);
    g = parse_gate("12ns:500ps");
    ASSERT_TRUE(g.error.empty()) << g.error;
    EXPECT_DOUBLE_EQ(g.start_ns, 12);
    EXPECT_DOUBLE_EQ(g.width_ns, 0.5);
    for (const char* bad : {"12", "12:", ":3", "12:0", "12:-1", "a:b", "12:3:4", "12s:3"})
        EXPECT_FALSE(parse_gate(bad).error.empty()) << bad;
}

TEST(SensorOptions, TheCommandLineTakesThemWithAnExrFolder) {
    const char* argv[] = {"slowlight", "render", "--exr-dir", "e", "--phasor", "20MHz", "--gate", "1:2",
                          "--first-arrival", "--first-arrival-threshold", "0.25", "--cube", "c.npy",
                          "--cube-layout", "mitransient", "--hdf5", "c.h5"};
    RunOptions r = parse_command_line(static_cast<int>(std::size(argv)), argv);
    EXPECT_EQ(r.sensors.phasor_hz, std::vector<double>{2e7});
    EXPECT_EQ(*r.sensors.gate_start_ns, 1);
    EXPECT_EQ(*r.sensors.gate_width_ns, 2);
    EXPECT_TRUE(r.sensors.first_arrival);
    EXPECT_EQ(r.sensors.first_arrival_threshold, 0.25);
    EXPECT_EQ(r.cube_layout, CubeLayout::Mitransient);
    EXPECT_EQ(r.hdf5_path, "c.h5");
    const char* no_dir[] = {"slowlight", "render", "-o", "v.mp4", "--gate", "1:2"};
    EXPECT_THROW(parse_command_line(6, no_dir), InputError);
}

}  // namespace
}  // namespace sl
