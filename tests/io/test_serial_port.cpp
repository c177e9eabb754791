// The serial port and the emulated URG behind a pseudo-terminal: the driver's whole path (open,
// raw mode, write, poll, read, time-out, hang-up) against the emulator, as a sensor would meet it.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/emulated_port.hpp"
#include "surfgrow/io/serial_port.hpp"
#include "surfgrow/scanner/urg_driver.hpp"
#include "surfgrow/scanner/urg_emulator.hpp"

namespace surfgrow {
namespace {

using scanner::UrgDriver;
using scanner::UrgEmulator;
using namespace std::chrono_literals;

std::vector<std::uint32_t> room() {  // 2 m in front, 1 m to the sides
    std::vector<std::uint32_t> mm(UrgEmulator::kSteps);
    for (int s = 0; s < UrgEmulator::kSteps; ++s) {
        const double a = (s - UrgEmulator::kFrontStep) * 2 * M_PI / 1024;
        const double front = 2.0 / std::max(std::cos(a), 1e-3);
        const double side = 1.0 / std::max(std::abs(std::sin(a)), 1e-3);
        mm[static_cast<std::size_t>(s)] =
            static_cast<std::uint32_t>(1000 * (std::cos(a) > 0 ? std::min(front, side) : side));
    }
    return mm;
}

TEST(SerialPort, TheDriverScansAnEmulatedUrgThroughAPseudoTerminal) {
    scanner::UrgFaults faults;
    faults.dropped = {1};  // the second scan's reply never comes: a time-out, then again
    UrgEmulator urg(room, faults);
    io::EmulatedPort port([&](std::string_view line) { return urg.reply(line); });
    io::SerialPort serial(port.path(), 115200, 300ms);
    UrgDriver driver([&](std::string_view c) { return serial.exchange(c); });
    const scanner::UrgIdentity id = driver.connect();
    EXPECT_EQ(id.product, "SOKUIKI Sensor URG-04LX");
    const std::vector<std::uint32_t> truth = room();
    const std::vector<std::uint32_t> want(truth.begin() + 44, truth.begin() + 726);
    EXPECT_EQ(driver.scan(44, 725), want);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(driver.scan(44, 725), want);
    EXPECT_EQ(driver.retries(), 1);
    EXPECT_GE(std::chrono::steady_clock::now() - start, 300ms);  // it waited out the time-out
    driver.close();
    EXPECT_FALSE(urg.laser_on());
}

TEST(SerialPort, AnUnpluggedSensorIsAClearError) {
    UrgEmulator urg(room);
    auto port =
        std::make_unique<io::EmulatedPort>([&](std::string_view l) { return urg.reply(l); });
    io::SerialPort serial(port->path(), 115200, 300ms);
    EXPECT_FALSE(serial.exchange("VV\n").empty());
    port.reset();  // unplugged
    try {
        (void)serial.exchange("VV\n");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCannotWrite);
        EXPECT_NE(std::string(e.what()).find("unplugged"), std::string::npos) << e.what();
    }
}

TEST(SerialPort, WhatIsNotAPortIsRefusedByName) {
    try {
        io::SerialPort p("/dev/ttyACM-none");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCannotOpen);
        EXPECT_NE(std::string(e.what()).find("/dev/ttyACM-none: No such file"), std::string::npos)
            << e.what();
    }
    try {
        io::SerialPort p("/dev/null");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kCannotOpen);
        EXPECT_NE(std::string(e.what()).find("not a serial port"), std::string::npos) << e.what();
    }
    UrgEmulator urg(room);
    io::EmulatedPort port([&](std::string_view l) { return urg.reply(l); });
    try {
        io::SerialPort p(port.path(), 12345);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParameter);
    }
}

}  // namespace
}  // namespace surfgrow
