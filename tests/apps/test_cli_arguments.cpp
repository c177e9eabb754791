// Every argument bounded (issue 17): absurd values for any option the CLI accepts end in a clear
// one-line message naming the option and a distinct exit code, never a signal, a hang or a
// silent overflow. One test per class: threads, lengths against the float range, lengths against
// the cloud's extent, seeds, counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "support/test_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

std::string q(const fs::path& p) {
    return test::quoted(p);
}

// Under a time limit: a hang fails the test instead of the whole run. Killed by the limit or by
// any signal, the shell reports a status of 128 or more.
CliRun surfgrow(const std::string& args) {
    return test::run_surfgrow(args, "timeout -s KILL 120 ");
}

struct Case {
    std::string args;
    int code;
    std::vector<std::string> said;  // in the output, in any order
};

constexpr int kUsage = static_cast<int>(ErrorCode::kUsage);
constexpr int kInvalid = static_cast<int>(ErrorCode::kInvalidParameter);

void expect_outcome(const Case& c) {
    const CliRun r = surfgrow(c.args);
    EXPECT_EQ(r.code, c.code) << c.args << "\n" << r.out;
    EXPECT_TRUE(r.code >= 0 && r.code < 124) << "a signal or the time limit: " << c.args;
    for (const std::string& s : c.said)
        EXPECT_NE(r.out.find(s), std::string::npos) << c.args << ": no '" << s << "' in\n" << r.out;
    for (const char* never : {"terminate", "internal error", "Aborted", "Segmentation"})
        EXPECT_EQ(r.out.find(never), std::string::npos) << c.args << "\n" << r.out;
    if (c.code != 0) {
        // One line: the message, nothing else (CLI11's own errors add a hint line).
        const std::size_t lines =
            static_cast<std::size_t>(std::count(r.out.begin(), r.out.end(), '\n'));
        EXPECT_LE(lines, c.code == kUsage ? 2u : 1u) << c.args << "\n" << r.out;
    }
}

// A grown box with bound planes: the inputs of every command that reads a result.
class CliArguments : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir();
        box_ = new test::GrownBox(test::grow_box(dir_->path()));
        const CliRun r =
            test::run_surfgrow(cat({"planes ", q(box_->out), " --cloud ", q(box_->cloud), " -q"}));
        ASSERT_EQ(r.code, 0) << r.out;
    }
    static void TearDownTestSuite() {
        delete box_;
        delete dir_;
    }
    static std::string grow() {
        return cat({"grow ", q(box_->cloud), " -o ", q(dir_->path() / "g"),
                    " -q --no-picture --no-occupancy --no-octomap --no-collision"});
    }
    static std::string result() { return q(box_->out); }
    static std::string cloud() { return q(box_->cloud); }
    static fs::path out(const char* name) { return dir_->path() / name; }

    static test::TempDir* dir_;
    static test::GrownBox* box_;
};

test::TempDir* CliArguments::dir_ = nullptr;
test::GrownBox* CliArguments::box_ = nullptr;

// --threads 100000 crashed with SIGSEGV: every command that takes --threads clamps it to what
// the machine can use, says so once on stderr, and gives the result of any other count. A
// negative count is refused; a count beyond int is clamped as well.
TEST_F(CliArguments, ThreadsAreClampedWithOneNoteForEveryCommand) {
    const std::vector<std::string> commands = {
        grow(),
        cat({"planes ", result(), " --cloud ", cloud(), " -q"}),
        cat({"coverage ", result(), " -q"}),
        cat({"occupancy ", result(), " --cloud ", cloud(), " -q --no-octomap"}),
        cat({"render ", result(), " -o ", q(out("r.png")), " --size 64x48 -q"}),
        cat({"sweep ", cloud(), " -o ", q(out("sweep")), " --mu 12mm -q"}),
    };
    for (const std::string& command : commands) {
        for (const char* n : {"100000", "2147483648", "9223372036854775808"}) {
            const CliRun r = surfgrow(cat({command, " --threads ", n}));
            EXPECT_EQ(r.code, 0) << command << "\n" << r.out;
            const std::string note = cat({"--threads ", n, " is more than this machine can use"});
            const std::size_t first = r.out.find(note);
            EXPECT_NE(first, std::string::npos) << command << "\n" << r.out;
            EXPECT_EQ(r.out.find(note, first + 1), std::string::npos) << "twice: " << r.out;
        }
        expect_outcome({cat({command, " --threads -1"}),
                        kInvalid,
                        {"--threads must be 0 (all cores) or more, got -1"}});
    }
    // Only whole numbers: digits beyond int followed by text are a usage error, not clamped
    // (found by fuzz/cli_args).
    for (const char* n : {"322222222222go2", "2147483648x", "-99999999999x", "4x"}) {
        const CliRun r = surfgrow(cat({grow(), " --threads ", n}));
        EXPECT_EQ(r.code, kUsage) << n << "\n" << r.out;
        EXPECT_EQ(r.out.find("more than this machine can use"), std::string::npos) << r.out;
    }
}

// Lengths a float cloud cannot express: beyond 3.4e38, below 1.2e-38, beyond a double, NaN, Inf.
// Refused before any work, naming the option and the value as typed (--mu 1e40m once overflowed
// into "fewer than 10 neighbours within 1e+40 m"; --closing 1e308m ended in std::terminate and
// --blast-radius 1e308m in a hang).
TEST_F(CliArguments, LengthsBeyondTheFloatRangeAreRefused) {
    const std::string beyond = "is beyond the range of float coordinates";
    const std::string below = "is below the smallest length float coordinates resolve";
    const std::vector<Case> cases = {
        {grow() + " --mu 1e40m", kInvalid, {"--mu: 1e40m ", beyond}},
        {grow() + " --mu 1e308m", kInvalid, {"--mu: 1e308m ", beyond}},
        {grow() + " --mu 1e400m", kInvalid, {"--mu: 1e400m is beyond the range of any length"}},
        {grow() + " --mu nanm", kInvalid, {"--mu: nanm is not a finite length"}},
        {grow() + " --mu infm", kInvalid, {"--mu: infm is not a finite length"}},
        {grow() + " --mu -infm", kInvalid, {"--mu: -infm is not a finite length"}},
        {grow() + " --mu 1e-300m", kInvalid, {"--mu: 1e-300m ", below}},
        {grow() + " --mu -0m", kInvalid, {"mu must be a positive length"}},
        // In the cloud's units (here mm) the library checks the same range.
        {grow() + " --units mm --mu 1e37m", kInvalid, {"surfgrow: error: mu = ", beyond}},
        {grow() + " --mu-max 1e39m", kInvalid, {"--mu-max: 1e39m ", beyond}},
        {grow() + " --plane-tol 1e-320m", kInvalid, {"--plane-tol: 1e-320m ", below}},
        {grow() + " --range-band 1e-300m", kInvalid, {"--range-band: 1e-300m ", below}},
        {grow() + " --crop-radius 1e39m", kInvalid, {"--crop-radius: 1e39m ", beyond}},
        {grow() + " --viewpoint 1e300,0,0m", kInvalid, {"--viewpoint: 1e300 ", beyond}},
        {grow() + " --crop-box -1e39,-1,-1,1,1,1m", kInvalid, {"--crop-box: -1e39 ", beyond}},
        {grow() + " --standoff 1e39m", kInvalid, {"--standoff: 1e39m ", beyond}},
        {cat({"planes ", result(), " --cloud ", cloud(), " --closing 1e308m"}),
         kInvalid,
         {"--closing: 1e308m ", beyond}},
        {cat({"planes ", result(), " --cloud ", cloud(), " --resolution 1e308m"}),
         kInvalid,
         {"--resolution: 1e308m ", beyond}},
        {cat({"coverage ", result(), " --blast-radius 1e308m"}),
         kInvalid,
         {"--blast-radius: 1e308m ", beyond}},
        {cat({"coverage ", result(), " --start 0,0,1e400m"}),
         kInvalid,
         {"--start: 1e400m is beyond the range of any length"}},
        {cat({"occupancy ", result(), " --cloud ", cloud(), " --viewpoint 0,nan,0m"}),
         kInvalid,
         {"--viewpoint: nan is not a finite length"}},
        {cat({"scan -o ", q(out("scan")), " --pose-error 1e39m"}),
         kInvalid,
         {"--pose-error: 1e39m ", beyond}},
    };
    for (const Case& c : cases) expect_outcome(c);
}

// Lengths that float coordinates hold, but absurd against this cloud: refused with the cloud's
// own figure where the work would explode (a hang, gigabytes) or mean nothing; computed
// correctly where they merely make a coarse or an empty result.
TEST_F(CliArguments, LengthsAgainstTheCloudsExtent) {
    const std::vector<Case> cases = {
        {grow() + " --mu 1e30m", kInvalid, {"larger than the whole cloud"}},
        {grow() + " --mu 1e-9m", kInvalid, {"finer than the cloud's float coordinates"}},
        {cat({"planes ", result(), " --cloud ", cloud(), " --adjacency 1m"}),
         kInvalid,
         {"adjacency distance", "4 mu"}},
        {cat({"coverage ", result(), " --blast-radius 1um"}),
         kInvalid,
         {"blast radius 1e-06 is too small for planes up to"}},
        // Once a std::bad_alloc in a parallel loop (std::terminate), then minutes of work.
        {cat({"coverage ", result(), " --spacing 1e-30m"}),
         kInvalid,
         {"sample spacing 1e-30 is finer than the blast radius / 16"}},
        {cat({"coverage ", result(), " --blast-radius 1e38m -q"}), 0, {}},
        {cat({"planes ", result(), " --cloud ", cloud(), " --closing 1e38m -q"}), 0, {}},
        {cat({"planes ", result(), " --cloud ", cloud(), " --max-gap 1e38m -q"}), 0, {}},
        {grow() + " --crop-radius 1e38m", 0, {}},
        {grow() + " --range-band 1e38m", 0, {}},
        {grow() + " --viewpoint 1e38,0,0m", 0, {}},
    };
    for (const Case& c : cases) expect_outcome(c);
}

// A seed is any whole number from 0 to 2^64 - 1; CLI11 alone saturated 2^64 and wrapped -1 to
// 2^64 - 1 without a word.
TEST_F(CliArguments, SeedsOutOfRangeAreRefused) {
    const std::string range = "is out of range (a whole number from 0 to 18446744073709551615)";
    const std::vector<Case> cases = {
        {grow() + " --seed 18446744073709551615", 0, {}},
        {grow() + " --seed 0", 0, {}},
        {grow() + " --seed 18446744073709551616",
         kInvalid,
         {"--seed: 18446744073709551616 " + range}},
        {grow() + " --seed 99999999999999999999999", kInvalid, {"--seed: 9999"}},
        {grow() + " --seed -1", kInvalid, {"--seed: -1 " + range}},
        {grow() + " --seed 1e3", kUsage, {"--seed"}},
        {grow() + " --seed nan", kUsage, {"--seed"}},
        {cat({"scan -o ", q(out("scan")), " --seed -5"}), kInvalid, {"--seed: -5 " + range}},
    };
    for (const Case& c : cases) expect_outcome(c);
}

// Counts: beyond int is a usage error naming the option; within int but absurd, a range error
// (--trim 2^30 once overflowed n > 2q; --min-pts 10^6 ran to zero surfaces without a word).
TEST_F(CliArguments, CountsOutOfRangeAreRefused) {
    const std::vector<Case> cases = {
        {grow() + " --min-pts 2147483648", kUsage, {"--min-pts"}},
        {grow() + " --min-pts 1000000", kInvalid, {"min-pts must be at most 100000"}},
        {grow() + " --min-pts -1", kInvalid, {"min-pts must be at least 3"}},
        {grow() + " --min-new 0", kInvalid, {"min-new-points"}},
        {grow() + " --min-new 9223372036854775808", kUsage, {"--min-new"}},
        {grow() + " --pool-angle 1e308", kInvalid, {"pool-angle"}},
        {grow() + " --pool-angle nan", kInvalid, {"pool-angle"}},
        {cat({"view ", result(), " -o ", q(out("v.html")), " --max-points 9223372036854775808"}),
         kInvalid,
         {"--max-points: 9223372036854775808 is out of range"}},
        {cat({"view ", result(), " -o ", q(out("v.html")), " --max-points -1"}),
         kInvalid,
         {"--max-points"}},
        {cat({"scan -o ", q(out("scan")), " --trim 1073741824"}), kInvalid, {"n must exceed 2q"}},
        {cat({"scan -o ", q(out("scan")), " --trim 2147483647"}), kInvalid, {"n must exceed 2q"}},
        {cat({"scan -o ", q(out("scan")), " --readings 2147483647"}), kInvalid, {"readings"}},
        {cat({"scan -o ", q(out("scan")), " --poses 1001"}), kInvalid, {"1000"}},
        {cat({"scan -o ", q(out("scan")), " --poses 0"}), kInvalid, {"poses"}},
        {cat({"sweep ", cloud(), " -o ", q(out("sw")), " --steps 2147483647"}),
         kInvalid,
         {"--steps"}},
        {cat({"sweep ", cloud(), " -o ", q(out("sw")), " --repeat 1000000"}),
         kInvalid,
         {"--repeat"}},
        {cat({"study -o ", q(out("st")), " --poses 2147483647"}), kInvalid, {"--poses"}},
        {cat({"study -o ", q(out("st")), " --steps 2147483647"}), kInvalid, {"--steps"}},
        {cat({"render ", result(), " -o ", q(out("r.png")), " --size 2147483648x16"}),
         kUsage,
         {"--size"}},
        {cat({"demo -o ", q(out("demo")), " --poses 99999"}), kInvalid, {"poses"}},
    };
    for (const Case& c : cases) expect_outcome(c);
}

}  // namespace
}  // namespace surfgrow
