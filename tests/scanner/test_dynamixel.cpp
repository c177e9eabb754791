// DYNAMIXEL Protocol 2.0: the manual's example packets byte for byte, byte stuffing, damaged
// packets refused, and the driver tilting an emulated servo: the angle it returns is the one the
// servo reports, lag and all; a stalled or silent servo is a clear error.
#include <gtest/gtest.h>

#include <string>

#include "surfgrow/scanner/servo_driver.hpp"
#include "surfgrow/scanner/servo_emulator.hpp"

namespace surfgrow::scanner::dxl {
namespace {

std::string bytes(std::initializer_list<int> b) {
    std::string s;
    for (const int x : b) s.push_back(static_cast<char>(x));
    return s;
}

TEST(Dynamixel, TheManualsExamplePackets) {
    EXPECT_EQ(packet(1, kPing),
              bytes({0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E}));
    EXPECT_EQ(packet(1, kRead, le_bytes(132, 2) + le_bytes(4, 2)),
              bytes({0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x02, 0x84, 0x00, 0x04, 0x00, 0x1D,
                     0x15}));
    EXPECT_EQ(ticks_of(0), 2048);
    EXPECT_EQ(ticks_of(90), 3072);
    EXPECT_DOUBLE_EQ(degrees_of(1024), -90.0);
}

TEST(Dynamixel, FfFfFdInTheParametersIsStuffedAndRestored) {
    const std::string params = bytes({0x74, 0x00, 0xFF, 0xFF, 0xFD, 0x07});
    const std::string p = packet(3, kWrite, params);
    EXPECT_NE(p.find(bytes({0xFF, 0xFF, 0xFD, 0xFD, 0x07})), std::string::npos);
    EXPECT_EQ(from_le(std::string_view(p).substr(5, 2)), 1u + 7u + 2u);  // stuffed byte counted
    const Packet back = parse(p);
    EXPECT_EQ(back.id, 3);
    EXPECT_EQ(back.instruction, kWrite);
    EXPECT_EQ(back.params, params);
}

TEST(Dynamixel, DamagedPacketsAreRefusedNeverACrash) {
    const std::string good = packet(1, kStatus, bytes({0x00, 0x10, 0x20}));
    ASSERT_NO_THROW((void)parse(good));
    std::string crc = good;
    crc.back() ^= 1;
    EXPECT_THROW((void)parse(crc), ServoError);
    std::string header = good;
    header[2] = 0;
    EXPECT_THROW((void)parse(header), ServoError);
    EXPECT_THROW((void)parse(good + "x"), ServoError);
    for (std::size_t k = 0; k < good.size(); ++k)
        EXPECT_THROW((void)parse(std::string_view(good).substr(0, k)), ServoError) << k;
}

TEST(Dynamixel, TheDriverReturnsTheAngleTheServoReportsNotTheOneAskedFor) {
    ServoFaults faults;
    faults.lag_ticks = -7;    // a loaded tilt unit settles 0.6 deg short
    faults.dropped = {0, 3};  // the ping's first status, and one poll's
    faults.corrupt = {5};     // and one status with a wrong CRC: asked for again
    ServoEmulator servo(1, 40, faults);
    ServoDriver driver([&](std::string_view p) { return servo.reply(p); });
    driver.connect();
    const double at = driver.tilt_to(30.0);
    EXPECT_EQ(ticks_of(at), ticks_of(30.0) - 7);
    EXPECT_NEAR(at, 30.0 - 7 * 360.0 / 4096, 360.0 / 4096);  // the goal's tick, 7 short
    EXPECT_EQ(driver.tilt_to(-60.0), degrees_of(ticks_of(-60.0) - 7));
}

TEST(Dynamixel, AStalledSilentOrUnreachableServoIsAClearError) {
    ServoFaults faults;
    faults.stall_at = 2300;  // blocked at about 22 deg
    ServoEmulator servo(1, 40, faults);
    ServoDriver driver([&](std::string_view p) { return servo.reply(p); }, 1, 3, 50);
    driver.connect();
    EXPECT_NEAR(driver.tilt_to(10.0), 10.0, 360.0 / 4096);
    try {
        (void)driver.tilt_to(40.0);
        FAIL() << "no error";
    } catch (const ServoError& e) {
        EXPECT_NE(std::string(e.what()).find("still moving after 50 polls"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("stalled"), std::string::npos) << e.what();
    }
    EXPECT_EQ(servo.position(), 2300);
    ServoDriver wrong_id([&](std::string_view p) { return servo.reply(p); }, 2);
    try {
        wrong_id.connect();
        FAIL() << "no error";
    } catch (const ServoError& e) {
        EXPECT_NE(std::string(e.what()).find("servo 2: no reply to ping in 3 attempts (time-out)"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW((void)driver.tilt_to(200.0), ServoError);
}

}  // namespace
}  // namespace surfgrow::scanner::dxl
