// SCIP 2.0: the published examples (encodings, checksums, status lines), round trips of every
// value and reply shape, and the emulated URG-04LX answering commands as the protocol says,
// faults included; every malformed reply a clear ProtocolError, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "surfgrow/scanner/scip.hpp"
#include "surfgrow/scanner/urg_driver.hpp"
#include "surfgrow/scanner/urg_emulator.hpp"

namespace surfgrow::scanner {
namespace {

using scip::ProtocolError;

TEST(Scip, ThePublishedExamples) {
    EXPECT_EQ(scip::encode(1234, 2), "CB");
    EXPECT_EQ(scip::encode(5432, 3), "1Dh");
    EXPECT_EQ(scip::decode("CB"), 1234u);
    EXPECT_EQ(scip::decode("1Dh"), 5432u);
    // Status lines every SCIP 2.0 reply carries: done, and MD/MS data.
    EXPECT_EQ(scip::checksum("00"), 'P');
    EXPECT_EQ(scip::checksum("99"), 'b');
    EXPECT_EQ(scip::command("BM"), "BM\n");
    EXPECT_EQ(scip::command(scip::DistanceRequest{}, "s1"), "GD0044072501;s1\n");
    scip::DistanceRequest md;
    md.continuous = true;
    md.three_chars = false;
    md.first_step = 0;
    md.last_step = 768;
    md.cluster = 3;
    md.skip_scans = 1;
    md.scans = 12;
    EXPECT_EQ(scip::command(md), "MS0000076803112\n");
}

TEST(Scip, EveryValueRoundTripsAndNoneOverflows) {
    for (const int chars : {2, 3, 4}) {
        const std::uint32_t top = (1u << (6 * chars)) - 1;
        for (std::uint32_t v : {0u, 1u, 63u, 64u, top / 2, top})
            EXPECT_EQ(scip::decode(scip::encode(v, chars)), v) << v << " in " << chars;
        EXPECT_THROW((void)scip::encode(top + 1, chars), std::invalid_argument);
    }
    for (const char* bad : {"", "0p", "0/", "1234567"})
        EXPECT_THROW((void)scip::decode(bad), ProtocolError) << bad;
    EXPECT_THROW((void)scip::command("GD", "a;b"), std::invalid_argument);
    EXPECT_THROW((void)scip::command("GD", "seventeen letters"), std::invalid_argument);
}

TEST(Scip, RepliesRoundTripOverLineBreaks) {
    std::mt19937 rng(3);
    std::uniform_int_distribution<std::uint32_t> mm(0, 262143);
    for (const std::size_t n : {0u, 1u, 21u, 22u, 64u, 682u}) {  // 21 3-char values = 63 chars
        std::vector<std::uint32_t> values(n);
        for (auto& v : values) v = mm(rng);
        std::vector<std::string> lines{scip::encode(123456, 4)};
        for (const std::string& l : scip::data_lines(values, 3)) lines.push_back(l);
        const std::string bytes = scip::format_reply("GD0044072501", "00", lines);
        const scip::Reply r = scip::parse_reply(bytes);
        EXPECT_EQ(r.echo, "GD0044072501");
        EXPECT_EQ(r.status, "00");
        EXPECT_EQ(r.time_stamp(), 123456u);
        EXPECT_EQ(r.distances(3), values);
        for (std::size_t k = 1; k < r.lines.size(); ++k) EXPECT_LE(r.lines[k].size(), 64u);
    }
}

// Data characters include ':' and ';': a data line that ends like an information line is
// still summed whole; only VV, PP and II lines leave their ';' out.
TEST(Scip, DataLinesAreSummedWholeInformationLinesWithoutTheirSemicolon) {
    ASSERT_EQ(scip::encode(651, 3), "0:;");
    const std::vector<std::string> data{scip::encode(9, 4), "0:;"};
    const std::string gd = scip::format_reply("GD0044004401", "00", data);
    EXPECT_EQ(gd[gd.size() - 3], scip::checksum("0:;"));
    EXPECT_EQ(scip::parse_reply(gd).distances(3), std::vector<std::uint32_t>{651});
    const std::vector<std::string> info{"PROT:SCIP 2.0;"};
    const std::string vv = scip::format_reply("VV", "00", info);
    EXPECT_EQ(vv[vv.size() - 3], scip::checksum("PROT:SCIP 2.0"));
    EXPECT_EQ(scip::parse_reply(vv).lines, info);
}

TEST(Scip, MalformedRepliesAreProtocolErrorsNamingTheLine) {
    const std::vector<std::string> lines{scip::encode(7, 4), "0C00C00C0"};
    const std::string good = scip::format_reply("GD0044004601", "00", lines);
    ASSERT_EQ(scip::parse_reply(good).distances(3).size(), 3u);
    std::string bad_sum = good;
    bad_sum[bad_sum.size() - 3] ^= 1;  // the data line's checksum
    try {
        (void)scip::parse_reply(bad_sum);
        FAIL() << "no error";
    } catch (const ProtocolError& e) {
        EXPECT_NE(std::string(e.what()).find("GD reply, line 4: checksum"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW((void)scip::parse_reply(good.substr(0, good.size() - 1)), ProtocolError);
    EXPECT_THROW((void)scip::parse_reply(good + "x"), ProtocolError);
    EXPECT_THROW((void)scip::parse_reply("GD\n\n"), ProtocolError);
    EXPECT_THROW((void)scip::parse_reply("GD\n00Q\n\n"), ProtocolError);  // status checksum
    EXPECT_THROW((void)scip::parse_reply("GD\n00P\n" + std::string(70, '0') + "\n\n"),
                 ProtocolError);
    // Every truncation of a good reply is an error or a shorter reply, never a crash.
    for (std::size_t k = 0; k < good.size(); ++k) {
        try {
            (void)scip::parse_reply(std::string_view(good).substr(0, k));
        } catch (const ProtocolError&) {
        }
    }
}

// A scan of the emulator: a wall 1 m in front, seen at every step (range 1 m / cos(angle)).
std::vector<std::uint32_t> wall() {
    std::vector<std::uint32_t> mm(UrgEmulator::kSteps, 0);
    for (int s = 0; s < UrgEmulator::kSteps; ++s) {
        const double a = (s - UrgEmulator::kFrontStep) * 2 * M_PI / 1024;
        mm[static_cast<std::size_t>(s)] =
            std::abs(a) < 1.4 ? static_cast<std::uint32_t>(1000 / std::cos(a)) : 0;
    }
    return mm;
}

TEST(UrgEmulator, AnswersTheHandshakeAndScansAsTheProtocolSays) {
    UrgEmulator urg(wall);
    EXPECT_EQ(scip::parse_reply(urg.reply("SCIP2.0\n")).status, "0");
    const scip::Reply vv = scip::parse_reply(urg.reply("VV\n"));
    EXPECT_EQ(vv.status, "00");
    EXPECT_EQ(vv.lines.at(3), "PROT:SCIP 2.0;");
    const scip::Reply pp = scip::parse_reply(urg.reply("PP\r\n"));
    EXPECT_EQ(pp.lines.at(6), "AFRT:384;");
    // The laser is off until BM: GD says so (status 10).
    EXPECT_EQ(scip::parse_reply(urg.reply(scip::command(scip::DistanceRequest{}))).status, "10");
    EXPECT_EQ(scip::parse_reply(urg.reply("BM;on\n")).echo, "BM;on");
    EXPECT_EQ(scip::parse_reply(urg.reply("BM\n")).status, "02");  // already on
    const scip::Reply gd =
        scip::parse_reply(urg.reply(scip::command(scip::DistanceRequest{}, "t")));
    EXPECT_EQ(gd.echo, "GD0044072501;t");
    const std::vector<std::uint32_t> d = gd.distances(3);
    ASSERT_EQ(d.size(), 682u);
    EXPECT_EQ(d[384 - 44], 1000u);  // the front step
    // Clusters report their nearest reading; GS clamps to 12 bits.
    scip::DistanceRequest gs;
    gs.three_chars = false;
    gs.cluster = 10;
    const std::vector<std::uint32_t> c =
        scip::parse_reply(urg.reply(scip::command(gs))).distances(2);
    EXPECT_EQ(c.size(), 69u);
    EXPECT_EQ(c[34], 1000u);  // steps 384..393
    for (const std::uint32_t v : c) EXPECT_LE(v, 4095u);
    // Time stamps advance by a scan (100 ms).
    const std::uint32_t t0 = gd.time_stamp();
    EXPECT_EQ(scip::parse_reply(urg.reply("GD0384038401\n")).time_stamp(), t0 + 200);
}

TEST(UrgEmulator, MdSendsEachScanWithTheScansStillToCome) {
    UrgEmulator urg(wall);
    scip::DistanceRequest md;
    md.continuous = true;
    md.scans = 3;
    md.first_step = 380;
    md.last_step = 389;
    std::string bytes = urg.reply(scip::command(md, "m"));
    EXPECT_TRUE(urg.laser_on());
    std::vector<std::string> echoes;
    for (std::size_t at = 0; at < bytes.size();) {
        const std::size_t end = bytes.find("\n\n", at) + 2;
        const scip::Reply r = scip::parse_reply(std::string_view(bytes).substr(at, end - at));
        echoes.push_back(r.echo + "/" + r.status);
        if (r.status == "99") {
            EXPECT_EQ(r.distances(3).size(), 10u);
        }
        at = end;
    }
    EXPECT_EQ(echoes, (std::vector<std::string>{"MD0380038901003;m/00", "MD0380038901002;m/99",
                                                "MD0380038901001;m/99", "MD0380038901000;m/99"}));
}

TEST(UrgEmulator, BadCommandsGetTheProtocolsErrorStatuses) {
    UrgEmulator urg(wall);
    (void)urg.reply("BM\n");
    const auto status = [&](const char* c) { return scip::parse_reply(urg.reply(c)).status; };
    EXPECT_EQ(status("XX\n"), "0E");
    EXPECT_EQ(status("GD004407250\n"), "0C");
    EXPECT_EQ(status("GDa044072501\n"), "01");
    EXPECT_EQ(status("GD0044x72501\n"), "02");
    EXPECT_EQ(status("GD00440725x1\n"), "03");
    EXPECT_EQ(status("GD0044080001\n"), "04");
    EXPECT_EQ(status("GD0400030001\n"), "05");
    EXPECT_EQ(status("GD0044072501;a-b\n"), "0H");
    EXPECT_EQ(status("GD0044072501;12345678901234567\n"), "0G");
}

TEST(UrgEmulator, InjectsCorruptDroppedAndUnpluggedReplies) {
    UrgFaults faults;
    faults.corrupt = {1};
    faults.dropped = {2};
    faults.unplugged_after = 4;
    UrgEmulator urg(wall, faults);
    (void)urg.reply("BM\n");
    const std::string gd = scip::command(scip::DistanceRequest{});
    EXPECT_NO_THROW((void)scip::parse_reply(urg.reply(gd)));              // 0: fine
    EXPECT_THROW((void)scip::parse_reply(urg.reply(gd)), ProtocolError);  // 1: corrupt
    EXPECT_EQ(urg.reply(gd), "");                                         // 2: dropped
    EXPECT_NO_THROW((void)scip::parse_reply(urg.reply(gd)));              // 3: fine
    EXPECT_EQ(urg.reply(gd), "");                                         // unplugged
    EXPECT_EQ(urg.reply("VV\n"), "");
}

// The driver against the emulator: identity, scans equal to what the sensor measured, and
// through lost and damaged replies by asking again.
TEST(UrgDriver, ConnectsAndScansThroughLostAndDamagedReplies) {
    UrgFaults faults;
    faults.corrupt = {0, 3};
    faults.dropped = {1};
    UrgEmulator urg(wall, faults);
    UrgDriver driver([&](std::string_view c) { return urg.reply(c); });
    const UrgIdentity id = driver.connect();
    EXPECT_EQ(id.product, "SOKUIKI Sensor URG-04LX");
    EXPECT_EQ(id.protocol, "SCIP 2.0");
    EXPECT_EQ(id.first_step, 44);
    EXPECT_EQ(id.last_step, 725);
    EXPECT_EQ(id.front_step, 384);
    EXPECT_EQ(id.steps_per_turn, 1024);
    EXPECT_TRUE(urg.laser_on());
    const std::vector<std::uint32_t> truth = wall();
    const std::vector<std::uint32_t> a = driver.scan(44, 725);  // replies 0, 1 lost; 2 good
    EXPECT_EQ(a, std::vector<std::uint32_t>(truth.begin() + 44, truth.begin() + 726));
    EXPECT_EQ(driver.retries(), 2);
    const std::vector<std::uint32_t> b = driver.scan(380, 389);  // 3 damaged, 4 good
    EXPECT_EQ(b, std::vector<std::uint32_t>(truth.begin() + 380, truth.begin() + 390));
    EXPECT_EQ(driver.retries(), 3);
    // The laser switched off behind the driver's back: turned on again.
    (void)urg.reply("QT\n");
    EXPECT_EQ(driver.scan(384, 384), std::vector<std::uint32_t>{1000});
    driver.close();
    EXPECT_FALSE(urg.laser_on());
}

TEST(UrgDriver, GarbledRepliesWithSoundChecksumsAreAskedForAgainThenRefused) {
    UrgFaults faults;
    faults.garbled = {0, 1, 3, 4, 5};
    UrgEmulator urg(wall, faults);
    // The checksums hold: only decoding the values finds them wrong.
    (void)urg.reply("BM\n");
    const scip::Reply bad = scip::parse_reply(urg.reply(scip::command(scip::DistanceRequest{})));
    EXPECT_THROW((void)bad.distances(3), ProtocolError);
    UrgDriver driver([&](std::string_view c) { return urg.reply(c); });
    (void)driver.connect();
    const std::vector<std::uint32_t> truth = wall();
    EXPECT_EQ(driver.scan(44, 725),
              std::vector<std::uint32_t>(truth.begin() + 44, truth.begin() + 726));
    EXPECT_EQ(driver.retries(), 1);  // reply 1 garbled, 2 fine
    try {
        (void)driver.scan(44, 725);  // 3, 4, 5 garbled: three attempts
        FAIL() << "no error";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("in 3 attempts"), std::string::npos) << e.what();
    }
}

TEST(UrgDriver, AnUnpluggedSensorIsADeviceErrorAfterTheAttempts) {
    UrgFaults faults;
    faults.unplugged_after = 1;
    UrgEmulator urg(wall, faults);
    int sent = 0;
    UrgDriver driver(
        [&](std::string_view c) {
            ++sent;
            return urg.reply(c);
        },
        4);
    (void)driver.connect();
    (void)driver.scan(44, 725);
    const int before = sent;
    try {
        (void)driver.scan(44, 725);
        FAIL() << "no error";
    } catch (const DeviceError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("no good reply to GD0044072501 in 4 attempts (time-out)"),
                  std::string::npos)
            << m;
        EXPECT_NE(m.find("unplugged"), std::string::npos) << m;
    }
    EXPECT_EQ(sent - before, 4);
    // A reply for another request (a late one) is not taken for this one.
    UrgEmulator late(wall);
    (void)late.reply("BM\n");
    const std::string stale = late.reply("GD0044072501;old\n");
    UrgDriver confused([&](std::string_view) { return stale; }, 2);
    try {
        (void)confused.scan(44, 725);
        FAIL() << "no error";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("a reply to another command"), std::string::npos)
            << e.what();
    }
    // A request the sensor refuses is not retried: its status is named.
    UrgEmulator urg2(wall);
    UrgDriver strict([&](std::string_view c) { return urg2.reply(c); });
    (void)strict.connect();
    try {
        (void)strict.scan(44, 900);
        FAIL() << "no error";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("status 04: the end step is beyond"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace surfgrow::scanner
