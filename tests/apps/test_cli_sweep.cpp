// End-to-end tests of `surfgrow sweep` and `surfgrow study`: the real binary, its CSV files read
// back and checked against the request, its PNG plots checked for size (when matplotlib is here).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "support/test_support.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow {
namespace {

namespace fs = std::filesystem;

struct CliRun {
    int code = -1;
    std::string out;  // stdout
    std::string err;  // stderr
};

// Runs the CLI with arguments (already shell-quoted where needed); `env` goes before it.
CliRun surfgrow(const std::string& args, const std::string& env = "") {
    static int count = 0;
    const fs::path err_file =
        fs::temp_directory_path() / cat({"surfgrow-sweep-test-", std::to_string(::getpid()), "-",
                                         std::to_string(count++), ".err"});
    const std::string cmd = cat({env, SURFGROW_CLI, " ", args, " 2>'", err_file.string(), "'"});
    CliRun r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe)) r.out += buf.data();
    const int status = pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.err = test::read_bytes(err_file);
    fs::remove(err_file);
    return r;
}

std::string q(const fs::path& p) {
    return cat({"'", p.string(), "'"});
}

// Plots are skipped (quickly) when the interpreter cannot run.
const std::string kNoPython = "SURFGROW_PYTHON=/nonexistent/python3 ";

bool have_matplotlib() {
    static const bool yes =
        std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0;
    return yes;
}

struct Csv {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;

    [[nodiscard]] std::size_t col(const std::string& name) const {
        for (std::size_t i = 0; i < header.size(); ++i)
            if (header[i] == name) return i;
        ADD_FAILURE() << "no column " << name;
        return 0;
    }
    [[nodiscard]] double at(std::size_t row, const std::string& name) const {
        const std::string& f = rows.at(row).at(col(name));
        return f.empty() ? std::nan("") : std::stod(f);
    }
    [[nodiscard]] std::vector<double> column(const std::string& name) const {
        std::vector<double> v;
        for (std::size_t r = 0; r < rows.size(); ++r) v.push_back(at(r, name));
        return v;
    }
};

std::vector<std::string> split_line(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream s(line);
    std::string f;
    while (std::getline(s, f, ',')) out.push_back(f);
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
}

Csv read_csv(const fs::path& file) {
    Csv csv;
    std::stringstream s(test::read_bytes(file));
    std::string line;
    if (std::getline(s, line)) csv.header = split_line(line);
    while (std::getline(s, line)) {
        csv.rows.push_back(split_line(line));
        EXPECT_EQ(csv.rows.back().size(), csv.header.size()) << file << ": " << line;
    }
    return csv;
}

// The CSV without its timing columns (everything from "seconds" on): what must not vary.
std::string without_timings(const fs::path& file) {
    const Csv csv = read_csv(file);
    const std::size_t keep = csv.col("seconds");
    std::string out;
    for (const auto* row : {&csv.header}) {
        for (std::size_t i = 0; i < keep; ++i) out += row->at(i) + ",";
        out += "\n";
    }
    for (const auto& row : csv.rows) {
        for (std::size_t i = 0; i < keep; ++i) out += row.at(i) + ",";
        out += "\n";
    }
    return out;
}

const std::vector<std::string> kTimings = {"seconds", "index_s", "grow_s", "attach_s", "finish_s"};

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// Width and height from a PNG's IHDR chunk; {0, 0} when the file is not a PNG.
std::pair<std::uint32_t, std::uint32_t> png_size(const fs::path& file) {
    const std::string b = test::read_bytes(file);
    if (b.size() < 24 || b.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || b.compare(12, 4, "IHDR") != 0)
        return {0, 0};
    auto be32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
        return v;
    };
    return {be32(16), be32(20)};
}

// Every file in a folder, by name, with its bytes.
std::map<std::string, std::string> folder_bytes(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::directory_iterator(dir))
        files[e.path().filename().string()] = test::read_bytes(e.path());
    return files;
}

// The outer faces of a box, 0.4 x 0.3 x 0.3 m, on a 5 mm grid with 1 mm noise (no ground
// truth): about 26 000 points, six planes.
PointCloud box_cloud() {
    PointCloud cloud;
    std::mt19937_64 rng(5);
    for (const auto& f : test::box_faces({-0.2, -0.15, 0.4}, {0.2, 0.15, 0.7}))
        test::sample_rect(f, 0.005, 0.3, 0.001, rng, cloud.points);
    return cloud;
}

class CliSweep : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir();
        io::write_cloud(box(), box_cloud());
        // The sweep every test reads: 4 mu values, 4 min-pts values, plots when possible.
        first_ = new CliRun(
            surfgrow(cat({"sweep ", q(box()), " --mu 12mm:48mm --steps 4 ",
                          "--min-pts 3:30 --min-pts-steps 4 --seed 2 -o ", q(sweep())})));
        // A room corner scanned from one pose: a cloud with ground truth beside it.
        const CliRun scan = surfgrow(
            cat({"scan --scene room-corner --poses 1 --seed 3 -q -o ", q(dir_->path() / "scan")}));
        ASSERT_EQ(scan.code, 0) << scan.err;
    }
    static void TearDownTestSuite() {
        delete first_;
        delete dir_;
    }
    static fs::path box() { return dir_->path() / "box.ply"; }
    static fs::path sweep() { return dir_->path() / "sweep"; }
    static fs::path scan() { return dir_->path() / "scan"; }
    static inline test::TempDir* dir_ = nullptr;
    static inline CliRun* first_ = nullptr;
    test::TempDir tmp_;

    // A sweep that must fail with `code`, leaving nothing at `out`.
    void expect_refused(const std::string& args, int code, const std::string& env = "") {
        const fs::path out = tmp_.path() / "refused";
        const CliRun r = surfgrow(cat({"sweep ", args, " -o ", q(out)}), env);
        EXPECT_EQ(r.code, code) << args << "\n" << r.err;
        EXPECT_FALSE(fs::exists(out)) << args;
        EXPECT_NE(r.err.find("error"), std::string::npos) << args << "\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << args << "\n" << r.out;
    }
};

TEST_F(CliSweep, WritesOneRowPerRequestedValue) {
    ASSERT_EQ(first_->code, 0) << first_->err;
    const Csv mu = read_csv(sweep() / "mu.csv");
    EXPECT_EQ(mu.header, concat({"mu_m", "min_pts", "points", "surfaces", "registered_pct",
                                 "registered_grown_pct", "reduction"},
                                kTimings));
    ASSERT_EQ(mu.rows.size(), 4u);
    // Log-spaced from 12 mm to 48 mm, rounded to 3 digits, the ends as given.
    const std::vector<double> mus = mu.column("mu_m");
    EXPECT_EQ(mu.rows.front()[0], "0.012");
    EXPECT_EQ(mu.rows.back()[0], "0.048");
    for (std::size_t i = 1; i < mus.size(); ++i) {
        EXPECT_GT(mus[i], mus[i - 1]);
        EXPECT_NEAR(mus[i] / mus[i - 1], std::pow(4.0, 1.0 / 3), 0.01);
    }
    for (std::size_t r = 0; r < mu.rows.size(); ++r) EXPECT_EQ(mu.at(r, "min_pts"), 10);

    const Csv mp = read_csv(sweep() / "min_pts.csv");
    EXPECT_EQ(mp.header, concat({"min_pts", "mu_m", "points", "surfaces", "registered_pct",
                                 "registered_grown_pct", "reduction"},
                                kTimings));
    ASSERT_EQ(mp.rows.size(), 4u);
    EXPECT_EQ(mp.column("min_pts"), (std::vector<double>{3, 12, 21, 30}));
    for (std::size_t r = 0; r < mp.rows.size(); ++r) EXPECT_EQ(mp.rows[r][1], "0.012");

    const std::size_t points = box_cloud().size();
    for (const Csv* csv : {&mu, &mp}) {
        for (std::size_t r = 0; r < csv->rows.size(); ++r) {
            EXPECT_EQ(csv->at(r, "points"), double(points));
            const double surfaces = csv->at(r, "surfaces");
            EXPECT_GT(surfaces, 0);
            for (const char* pct : {"registered_pct", "registered_grown_pct"}) {
                EXPECT_GE(csv->at(r, pct), 0);
                EXPECT_LE(csv->at(r, pct), 100);
            }
            EXPECT_LE(csv->at(r, "registered_grown_pct"), csv->at(r, "registered_pct") + 1e-9);
            EXPECT_NEAR(csv->at(r, "reduction"), double(points) / surfaces, 1e-3);
            for (const std::string& t : kTimings) EXPECT_GE(csv->at(r, t), 0) << t;
            const double stages = csv->at(r, "index_s") + csv->at(r, "grow_s") +
                                  csv->at(r, "attach_s") + csv->at(r, "finish_s");
            EXPECT_NEAR(csv->at(r, "seconds"), stages, 1e-5 + 0.01 * stages);
        }
    }
    // On six planes a larger neighbourhood means fewer, larger surfaces -- above the density
    // limit (10 points within mu on a 5 mm grid: mu of about 9 mm; below it the adaptive radius
    // and sparse home points make the count rise with mu, as on the I-beam in docs/studies.md).
    const std::vector<double> surfaces = mu.column("surfaces");
    for (std::size_t i = 1; i < surfaces.size(); ++i)
        EXPECT_LT(surfaces[i], surfaces[i - 1]) << test::read_bytes(sweep() / "mu.csv");
    // A dense box registers (almost) everything at mu >= 12 mm.
    for (const double pct : mu.column("registered_pct")) EXPECT_GT(pct, 95);

    const auto record = nlohmann::json::parse(test::read_bytes(sweep() / "sweep.json"));
    EXPECT_EQ(record.at("format"), "surfgrow-sweep");
    EXPECT_EQ(record.at("ground_truth"), false);
    EXPECT_EQ(record.at("points"), points);
    EXPECT_EQ(record.at("seed"), 2);
}

TEST_F(CliSweep, SummaryOnStdoutNothingElse) {
    ASSERT_EQ(first_->code, 0) << first_->err;
    EXPECT_NE(first_->out.find("sweep: "), std::string::npos) << first_->out;
    EXPECT_NE(first_->out.find("4 mu values 12 mm..48 mm at min_pts 10"), std::string::npos)
        << first_->out;
    EXPECT_NE(first_->out.find("4 min_pts values 3..30 at mu 12 mm"), std::string::npos)
        << first_->out;
    EXPECT_EQ(std::count(first_->out.begin(), first_->out.end(), '\n'), 1) << first_->out;
    // stderr is no terminal here: no progress, and no warning when the plots were drawn.
    if (have_matplotlib()) {
        EXPECT_TRUE(first_->err.empty()) << first_->err;
    }
}

TEST_F(CliSweep, DrawsOnePlotPerSweep) {
    if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib";
    ASSERT_EQ(first_->code, 0) << first_->err;
    for (const char* png : {"mu.png", "min_pts.png"}) {
        EXPECT_EQ(png_size(sweep() / png), (std::pair<std::uint32_t, std::uint32_t>{1600, 1200}))
            << png;
        EXPECT_GT(fs::file_size(sweep() / png), 20000u) << png;  // drawn, not blank
    }
    const auto record = nlohmann::json::parse(test::read_bytes(sweep() / "sweep.json"));
    EXPECT_EQ(record.at("files"),
              nlohmann::json::array({"mu.csv", "min_pts.csv", "mu.png", "min_pts.png"}));
}

TEST_F(CliSweep, SameInputSameResultsApartFromTimings) {
    const fs::path again = tmp_.path() / "again";
    const CliRun r =
        surfgrow(cat({"sweep ", q(box()), " --mu 12mm:48mm --steps 4 --min-pts 3:30 ",
                      "--min-pts-steps 4 --seed 2 --threads 1 --repeat 2 -q -o ", q(again)}),
                 kNoPython);
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* csv : {"mu.csv", "min_pts.csv"}) {
        EXPECT_EQ(without_timings(again / csv), without_timings(sweep() / csv)) << csv;
        // With --repeat the times are one run's, the median one: its stages add up.
        const Csv t = read_csv(again / csv);
        for (std::size_t i = 0; i < t.rows.size(); ++i) {
            const double stages =
                t.at(i, "index_s") + t.at(i, "grow_s") + t.at(i, "attach_s") + t.at(i, "finish_s");
            EXPECT_NEAR(t.at(i, "seconds"), stages, 1e-5 + 0.01 * stages) << csv;
        }
    }
    // Another seed, other home points: the same columns, other surfaces.
    const CliRun other =
        surfgrow(cat({"sweep ", q(box()), " --mu 12mm:48mm --steps 4 --seed 3 -q -o ",
                      q(tmp_.path() / "b")}),
                 kNoPython);
    ASSERT_EQ(other.code, 0) << other.err;
    EXPECT_NE(without_timings(tmp_.path() / "b" / "mu.csv"), without_timings(sweep() / "mu.csv"));
}

TEST_F(CliSweep, OnlyTheRequestedSweep) {
    const fs::path out = tmp_.path() / "mu-only";
    const CliRun r = surfgrow(
        cat({"sweep ", q(box()), " --mu 10mm,20mm,15mm --at-min-pts 8 -q -o ", q(out)}), kNoPython);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(fs::exists(out / "min_pts.csv"));
    const Csv mu = read_csv(out / "mu.csv");
    ASSERT_EQ(mu.rows.size(), 3u);
    EXPECT_EQ(mu.rows[0][0], "0.01");
    EXPECT_EQ(mu.rows[1][0], "0.015");
    EXPECT_EQ(mu.rows[2][0], "0.02");
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(mu.rows[i][1], "8");

    const CliRun mp = surfgrow(
        cat({"sweep ", q(box()), " --min-pts 5:7 --at-mu 20mm -q -o ", q(tmp_.path() / "mp")}),
        kNoPython);
    ASSERT_EQ(mp.code, 0) << mp.err;
    EXPECT_FALSE(fs::exists(tmp_.path() / "mp" / "mu.csv"));
    const Csv csv = read_csv(tmp_.path() / "mp" / "min_pts.csv");
    EXPECT_EQ(csv.column("min_pts"), (std::vector<double>{5, 6, 7}));  // 10 steps, 3 integers
    EXPECT_EQ(csv.rows[0][1], "0.02");
}

TEST_F(CliSweep, MillimetreCloudGivesTheSameTableInMetres) {
    PointCloud mm = box_cloud();
    for (Vec3f& p : mm.points) p *= 1000.0f;
    io::write_cloud(tmp_.path() / "box-mm.ply", mm);
    const CliRun r = surfgrow(
        cat({"sweep ", q(tmp_.path() / "box-mm.ply"),
             " --units mm --mu 12mm:48mm --steps 4 --seed 2 -q -o ", q(tmp_.path() / "mm")}),
        kNoPython);
    ASSERT_EQ(r.code, 0) << r.err;
    const Csv a = read_csv(tmp_.path() / "mm" / "mu.csv"), b = read_csv(sweep() / "mu.csv");
    ASSERT_EQ(a.rows.size(), b.rows.size());
    for (std::size_t i = 0; i < a.rows.size(); ++i) {
        EXPECT_EQ(a.rows[i][0], b.rows[i][0]);  // mu in metres either way
        EXPECT_NEAR(a.at(i, "surfaces"), b.at(i, "surfaces"), 0.05 * b.at(i, "surfaces"));
    }
}

TEST_F(CliSweep, GroundTruthAddsNormalError) {
    SURFGROW_SKIP_UNDER_SANITIZERS();
    // The scan folder's cloud.ply has a truth label per point, scene.json lies beside it.
    const fs::path out = tmp_.path() / "truth";
    const CliRun r = surfgrow(cat({"sweep ", q(scan() / "cloud.ply"),
                                   " --mu 8mm:32mm --steps 3 --min-pts 5,10 -o ", q(out)}),
                              kNoPython);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("with ground truth"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("plots skipped"), std::string::npos) << r.err;
    for (const char* name : {"mu.csv", "min_pts.csv"}) {
        const Csv csv = read_csv(out / name);
        EXPECT_EQ(std::vector<std::string>(csv.header.begin() + 2, csv.header.end()),
                  concat({"points", "surfaces", "registered_pct", "registered_grown_pct",
                          "reduction", "normal_err_median_deg", "normal_err_p95_deg"},
                         kTimings))
            << name;
        for (std::size_t r2 = 0; r2 < csv.rows.size(); ++r2) {
            const double median = csv.at(r2, "normal_err_median_deg");
            const double p95 = csv.at(r2, "normal_err_p95_deg");
            EXPECT_GE(median, 0) << name;
            EXPECT_LE(median, p95) << name;
            EXPECT_LE(p95, 90) << name;
            EXPECT_LT(median, 5) << name;  // a room of planes, scanned with datasheet noise
        }
    }
    EXPECT_EQ(read_csv(out / "mu.csv").rows.size(), 3u);
    EXPECT_EQ(read_csv(out / "min_pts.csv").rows.size(), 2u);
    EXPECT_EQ(nlohmann::json::parse(test::read_bytes(out / "sweep.json")).at("ground_truth"), true);

    // The scan folder itself names the same cloud: the same table.
    const CliRun dir = surfgrow(
        cat({"sweep ", q(scan()), " --mu 8mm:32mm --steps 3 -q -o ", q(tmp_.path() / "dir")}),
        kNoPython);
    ASSERT_EQ(dir.code, 0) << dir.err;
    EXPECT_EQ(without_timings(tmp_.path() / "dir" / "mu.csv"), without_timings(out / "mu.csv"));

    // The same cloud away from its scene file has no truth: no normal columns.
    fs::copy_file(scan() / "cloud.ply", tmp_.path() / "alone.ply");
    const CliRun alone = surfgrow(cat({"sweep ", q(tmp_.path() / "alone.ply"),
                                       " --mu 8mm:32mm --steps 3 -q -o ", q(tmp_.path() / "a")}),
                                  kNoPython);
    ASSERT_EQ(alone.code, 0) << alone.err;
    const Csv csv = read_csv(tmp_.path() / "a" / "mu.csv");
    EXPECT_EQ(std::count(csv.header.begin(), csv.header.end(), "normal_err_median_deg"), 0);
    // Truth is in metres: a cloud said to be in millimetres cannot be held against it.
    expect_refused(cat({q(scan() / "cloud.ply"), " --units mm --mu 8mm"}), 2);
}

TEST_F(CliSweep, PlotsSkippedWithAWarningUnlessRequired) {
    // No interpreter: the CSV files are written, a warning on stderr, success.
    const fs::path out = tmp_.path() / "no-plots";
    const CliRun r =
        surfgrow(cat({"sweep ", q(box()), " --mu 10mm:20mm --steps 2 -o ", q(out)}), kNoPython);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: plots skipped"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/nonexistent/python3"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("(CSV only)"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(out / "mu.csv"));
    EXPECT_TRUE(fs::exists(out / "sweep.json"));
    EXPECT_FALSE(fs::exists(out / "mu.png"));

    // No script where SURFGROW_PLOT_SCRIPT_DIR points: the same, and the message says where.
    const CliRun no_script = surfgrow(
        cat({"sweep ", q(box()), " --mu 10mm:20mm --steps 2 -q -o ", q(tmp_.path() / "s")}),
        cat({"SURFGROW_PLOT_SCRIPT_DIR=", q(tmp_.path()), " "}));
    ASSERT_EQ(no_script.code, 0) << no_script.err;
    EXPECT_NE(no_script.err.find("SURFGROW_PLOT_SCRIPT_DIR"), std::string::npos) << no_script.err;

    // A script that fails: its last words are in the warning.
    test::write_bytes(tmp_.path() / "surfgrow_plots.py",
                      "import sys\nprint('no display here', file=sys.stderr)\nsys.exit(3)\n");
    const CliRun failing = surfgrow(
        cat({"sweep ", q(box()), " --mu 10mm:20mm --steps 2 -q -o ", q(tmp_.path() / "f")}),
        cat({"SURFGROW_PLOT_SCRIPT_DIR=", q(tmp_.path()), " "}));
    ASSERT_EQ(failing.code, 0) << failing.err;
    EXPECT_NE(failing.err.find("no display here"), std::string::npos) << failing.err;

    // --require-plots: an error, nothing written, and an earlier good result is left alone.
    const auto before = folder_bytes(out);
    const CliRun required =
        surfgrow(cat({"sweep ", q(box()), " --mu 10mm:30mm --steps 3 --require-plots -o ", q(out)}),
                 kNoPython);
    EXPECT_EQ(required.code, 7) << required.err;
    EXPECT_NE(required.err.find("--require-plots"), std::string::npos) << required.err;
    EXPECT_EQ(folder_bytes(out), before);
    expect_refused(cat({q(box()), " --mu 10mm:20mm --steps 2 --require-plots"}), 7, kNoPython);
}

TEST_F(CliSweep, BadRangesAreRefusedBeforeAnyWork) {
    const std::string box_arg = q(box());
    expect_refused(cat({box_arg, " --mu 50mm:1mm"}), 3);     // decreasing
    expect_refused(cat({box_arg, " --mu 12mm:12mm"}), 3);    // empty
    expect_refused(cat({box_arg, " --mu 1:50"}), 2);         // no unit
    expect_refused(cat({box_arg, " --mu 1mm:50"}), 2);       // no unit on one end
    expect_refused(cat({box_arg, " --mu 0mm:5mm"}), 3);      // zero
    expect_refused(cat({box_arg, " --mu -5mm,5mm"}), 3);     // negative
    expect_refused(cat({box_arg, " --mu 1mm:5mm:9mm"}), 2);  // neither range nor list
    expect_refused(cat({box_arg, " --mu 1mm:50mm --steps 100000"}), 3);
    expect_refused(cat({box_arg, " --mu 1mm:50mm --steps 1"}), 3);
    expect_refused(cat({box_arg, " --min-pts 2:10"}), 3);  // a plane needs 3 points
    expect_refused(cat({box_arg, " --min-pts 10:3"}), 3);
    expect_refused(cat({box_arg, " --min-pts 3:x"}), 2);
    expect_refused(cat({box_arg, " --min-pts 3:40 --min-pts-steps 5000"}), 3);
    expect_refused(cat({box_arg, " --at-mu 12"}), 2);
    expect_refused(cat({box_arg, " --at-min-pts 2"}), 3);
    expect_refused(cat({box_arg, " --repeat 0"}), 3);
    expect_refused(cat({box_arg, " --alpha 0.5"}), 3);
}

TEST_F(CliSweep, MissingAndEmptyInputsAreRefused) {
    expect_refused(q(tmp_.path() / "missing.ply"), 4);
    io::write_cloud(tmp_.path() / "empty.ply", PointCloud{});
    expect_refused(q(tmp_.path() / "empty.ply"), 6);
    PointCloud nan;
    nan.points.assign(10, Vec3f::Constant(std::nanf("")));
    io::write_cloud(tmp_.path() / "nan.ply", nan);
    expect_refused(q(tmp_.path() / "nan.ply"), 6);
    test::write_bytes(tmp_.path() / "file", "x");
    const CliRun r = surfgrow(cat({"sweep ", q(box()), " --mu 10mm -o ", q(tmp_.path() / "file")}));
    EXPECT_EQ(r.code, 7) << r.err;
}

// ------------------------------------------------------------------------------------------------
// study

class CliStudy : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir();
        first_ = new CliRun(surfgrow(cat({"study --scene room-corner --poses 2 --sizes 5k,20k,60k,",
                                          "150k,300k --seed 4 -o ", q(study())})));
    }
    static void TearDownTestSuite() {
        delete first_;
        delete dir_;
    }
    static fs::path study() { return dir_->path() / "study"; }
    static inline test::TempDir* dir_ = nullptr;
    static inline CliRun* first_ = nullptr;
    test::TempDir tmp_;
};

TEST_F(CliStudy, OneTestPerSize) {
    ASSERT_EQ(first_->code, 0) << first_->err;
    EXPECT_NE(first_->out.find("study: 5 tests of 5000..300000 points from 2 poses of room-corner"),
              std::string::npos)
        << first_->out;
    const Csv csv = read_csv(study() / "study.csv");
    EXPECT_EQ(csv.header, concat({"test", "poses", "radius_m", "points", "surfaces",
                                  "registered_pct", "registered_grown_pct", "reduction"},
                                 kTimings));
    ASSERT_EQ(csv.rows.size(), 5u);
    EXPECT_EQ(csv.column("test"), (std::vector<double>{1, 2, 3, 4, 5}));
    EXPECT_EQ(csv.column("points"), (std::vector<double>{5000, 20000, 60000, 150000, 300000}));
    // One pose holds the small tests, the largest needs both; the cut grows with the test.
    EXPECT_EQ(csv.at(0, "poses"), 1);
    EXPECT_EQ(csv.at(4, "poses"), 2);
    for (std::size_t r = 0; r < csv.rows.size(); ++r) {
        if (r > 0) {
            EXPECT_GE(csv.at(r, "poses"), csv.at(r - 1, "poses"));
            if (csv.at(r, "poses") == csv.at(r - 1, "poses")) {
                EXPECT_GT(csv.at(r, "radius_m"), csv.at(r - 1, "radius_m"));
            }
        }
        EXPECT_GT(csv.at(r, "radius_m"), 0);
        EXPECT_GT(csv.at(r, "surfaces"), 0);
        EXPECT_GE(csv.at(r, "registered_pct"), 90);  // dense crops of planes
        EXPECT_LE(csv.at(r, "registered_pct"), 100);
        EXPECT_NEAR(csv.at(r, "reduction"), csv.at(r, "points") / csv.at(r, "surfaces"), 1e-3);
        for (const std::string& t : kTimings) EXPECT_GE(csv.at(r, t), 0) << t;
    }
    // More points, more surfaces (not test by test: a cut of two scans has other overlaps).
    EXPECT_GT(csv.at(4, "surfaces"), 2 * csv.at(0, "surfaces"));
    const auto record = nlohmann::json::parse(test::read_bytes(study() / "study.json"));
    EXPECT_EQ(record.at("format"), "surfgrow-study");
    EXPECT_EQ(record.at("scene"), "room-corner");
    EXPECT_EQ(record.at("tests"), 5);
}

TEST_F(CliStudy, DrawsScalingAndStages) {
    if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib";
    ASSERT_EQ(first_->code, 0) << first_->err;
    EXPECT_TRUE(first_->err.empty()) << first_->err;
    EXPECT_EQ(png_size(study() / "scaling.png"),
              (std::pair<std::uint32_t, std::uint32_t>{1600, 1200}));
    EXPECT_EQ(png_size(study() / "stages.png"),
              (std::pair<std::uint32_t, std::uint32_t>{1600, 900}));
    EXPECT_GT(fs::file_size(study() / "scaling.png"), 20000u);
    EXPECT_GT(fs::file_size(study() / "stages.png"), 20000u);
}

TEST_F(CliStudy, SameSeedSameResultsApartFromTimings) {
    const CliRun r = surfgrow(cat({"study --scene room-corner --poses 2 --sizes 5k,20k,60k,150k,",
                                   "300k --seed 4 --threads 1 -q -o ", q(tmp_.path() / "again")}),
                              kNoPython);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(without_timings(tmp_.path() / "again" / "study.csv"),
              without_timings(study() / "study.csv"));
    EXPECT_FALSE(fs::exists(tmp_.path() / "again" / "scaling.png"));
}

TEST_F(CliStudy, BadRequestsAreRefused) {
    auto refused = [&](const std::string& args, int code) {
        const fs::path out = tmp_.path() / "refused";
        const CliRun r = surfgrow(cat({"study ", args, " -o ", q(out)}), kNoPython);
        EXPECT_EQ(r.code, code) << args << "\n" << r.err;
        EXPECT_FALSE(fs::exists(out)) << args;
    };
    refused("--scene room-corner --poses 1 --sizes 50M", 3);  // more than the scans hold
    refused("--sizes 50k:10k", 3);
    refused("--sizes 10:100", 3);  // below 1000 points
    refused("--sizes 10k:1M --steps 1000", 3);
    refused("--sizes 10q", 2);
    refused("--poses 0", 3);
    refused("--poses 1000", 3);
    refused("--units mm", 2);
    refused("--mu 12", 2);
    refused("--min-pts 2", 3);
    refused("--scene no-such-scene", 3);
    refused("--scene room-corner --poses 1 --sizes 5k --require-plots", 7);
}

}  // namespace
}  // namespace surfgrow
