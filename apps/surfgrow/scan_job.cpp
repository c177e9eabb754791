#include "scan_job.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/ply.hpp"
#include "surfgrow/io/poses_file.hpp"
#include "surfgrow/io/raw_scan_format.hpp"
#include "surfgrow/io/scene_file.hpp"
#include "surfgrow/io/truth_faces_file.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/noise_model.hpp"
#include "surfgrow/scanner/range_filter.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

namespace surfgrow::cli {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void invalid(const std::string& message) {
    throw Error(ErrorCode::kInvalidParameter, message);
}

bool all_digits(std::string_view s) {
    if (s.empty()) return false;
    for (const char c : s) {
        if (c < '0' || c > '9') return false;
    }
    return true;
}

std::vector<scanner::Pose> load_poses(const std::string& poses, const scanner::ScanPath& path) {
    if (!all_digits(poses)) return io::read_poses_file(poses);
    int count = 0;  // "00001" is 1; beyond int is too many (scan_poses checks the rest)
    if (std::from_chars(poses.data(), poses.data() + poses.size(), count).ec != std::errc())
        invalid(cat({"--poses ", poses, ": at most 1000 poses"}));
    return scanner::scan_poses(path, count);
}

// A range limit in whole millimetres, or 0 for "the laser's own".
std::uint16_t range_mm(const std::string& text, const char* option) {
    if (text.empty()) return 0;
    const double mm = std::round(parse_length_m(text, option) * 1000.0);
    if (!(mm >= 1 && mm <= 65534))
        invalid(cat({option, " ", text, " lies outside any sensor's limits (1..65534 mm)"}));
    return static_cast<std::uint16_t>(mm);
}

std::string json_text(const nlohmann::json& j) {
    return j.dump(2) + "\n";
}

}  // namespace

// A scene file when it names one (or looks like one); a built-in scene otherwise.
scanner::SceneDescription load_scene(const std::string& name) {
    if (name.ends_with(".json") || name.find('/') != std::string::npos || fs::is_regular_file(name))
        return io::read_scene_file(name);
    return scanner::builtin_scene(name);
}

scanner::NoiseModel noise_model(const std::string& name) {
    if (name == "datasheet") return {};
    if (name == "ideal") return scanner::NoiseModel::ideal();
    throw Error(ErrorCode::kUsage,
                cat({"--noise: unknown model '", name, "' (use datasheet or ideal)"}));
}

// The optical centre's height above the tilt axis, metres: "0" alone is accepted (no unit needed
// for nothing), anything else needs its unit.
double optical_offset_m(const std::string& text) {
    if (text == "0") return 0.0;
    const double m = parse_length_m(text, "--optical-offset");
    if (!(std::abs(m) < 1.0))
        invalid(cat({"--optical-offset ", text, " must be under 1 m in size"}));
    return m;
}

// A folder without raw scans is an error: fusing nothing silently would hide a wrong path.
std::vector<std::string> raw_scan_files(const std::vector<std::string>& args) {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    for (const std::string& arg : args) {
        std::error_code ec;
        if (!fs::is_directory(arg, ec)) {
            files.push_back(arg);
            continue;
        }
        std::vector<std::string> found;
        for (const fs::directory_entry& e : fs::directory_iterator(arg, ec))
            if (e.path().extension() == ".sgraw") found.push_back(e.path().string());
        if (ec) throw Error(ErrorCode::kCannotOpen, cat({"cannot list ", arg, ": ", ec.message()}));
        if (found.empty())
            throw Error(ErrorCode::kCannotOpen,
                        cat({arg, ": no raw scans (.sgraw) in this folder"}));
        std::sort(found.begin(), found.end());
        files.insert(files.end(), found.begin(), found.end());
    }
    return files;
}

void refuse_partial(const std::string& file, const scanner::RawScan& raw, bool allowed,
                    std::string_view verb) {
    if (!raw.partial() || allowed) return;
    invalid(cat({file, ": a partial scan (", std::to_string(raw.spec.tilt.positions), " of ",
                 std::to_string(raw.planned_positions), " tilt positions; it stopped: ",
                 raw.stop_reason, "); --allow-partial ", verb, " it"}));
}

void ScanSettings::add_to(CLI::App& cmd) {
    cmd.add_option("--scene", scene,
                   "Built-in scene (ibeam-channel, room-corner, pipes, corridor, stairs) or a "
                   "scene file (.json)")
        ->capture_default_str();
    cmd.add_option("--poses", poses,
                   "Number of scans along the scene's scan path, or a poses file (text or JSON)")
        ->capture_default_str();
    add_seed_option(cmd, seed, "Random seed of the simulated noise");
    cmd.add_option("--readings", readings, "Readings per ray, n of eq. (1)")->capture_default_str();
    cmd.add_option("--trim", trim, "Readings trimmed from each end, q of eq. (1); n > 2q")
        ->capture_default_str();
    cmd.add_option("--laser", laser, "Laser preset: urg04lx-paper, urg04lx-682, urg04lx-769")
        ->capture_default_str();
    cmd.add_option("--noise", noise, "Sensor model: datasheet (URG-04LX) or ideal")
        ->capture_default_str();
    cmd.add_option("--min-range", min_range,
                   "Drop readings nearer than this when fusing (default: the laser's limit)");
    cmd.add_option("--max-range", max_range,
                   "Drop readings farther than this when fusing (default: the laser's limit)");
    cmd.add_option("--optical-offset", optical_offset,
                   "Laser optical centre above the tilt axis (0: on the axis, where all tilt "
                   "positions meet one spot at pan +-90 deg)")
        ->capture_default_str();
    cmd.add_option("--pose-error", pose_error,
                   "Sigma of a random error in each recorded scan position (e.g. 2mm): the cloud "
                   "is fused with poses that are slightly wrong, as a robot's are");
    cmd.add_option("--pose-error-angle", pose_error_deg,
                   "Sigma of a random error in each recorded scan orientation, degrees");
    add_veil_option(cmd, veil_angle_deg);
}

void add_veil_option(CLI::App& cmd, double& angle_deg) {
    cmd.add_option("--veil-angle", angle_deg,
                   "Drop mixed pixels: a ray whose two neighbours (along its line or across the "
                   "tilt rows) lie within this angle of its line of sight, one nearer and one "
                   "farther, more than 30 mm away (the blend of two ranges behind a silhouette), "
                   "degrees, e.g. 10 (off by default); 0 keeps every ray")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 45.0));
}

std::string veil_summary(const scanner::FuseReport& report) {
    std::uint64_t n = 0;
    for (const std::uint64_t k : report.veil_points) n += k;
    return n ? cat({"; ", std::to_string(n), " mixed pixels dropped"}) : std::string();
}

scanner::FuseOptions fuse_options(int readings, int trim, const std::string& min_range,
                                  const std::string& max_range, const scanner::LaserSpec& laser) {
    scanner::FuseOptions f;
    f.trim_q = trim;
    f.min_range_mm = range_mm(min_range, "--min-range");
    f.max_range_mm = range_mm(max_range, "--max-range");
    if (trim < 0) invalid(cat({"--trim must be at least 0, got ", std::to_string(trim)}));
    if (std::int64_t{readings} <= 2 * std::int64_t{trim})  // no overflow at --trim 2^30
        invalid(cat({"--trim ", std::to_string(trim), " leaves nothing of ",
                     std::to_string(readings), " readings per ray: n must exceed 2q"}));
    const std::uint16_t lo = f.min_range_mm ? f.min_range_mm : laser.min_range_mm;
    const std::uint16_t hi = f.max_range_mm ? f.max_range_mm : laser.max_range_mm;
    if (lo < laser.min_range_mm || hi > laser.max_range_mm || lo >= hi)
        invalid(cat({"range limits ", std::to_string(lo), "..", std::to_string(hi),
                     " mm must be increasing and lie within the sensor's limits ",
                     std::to_string(laser.min_range_mm), "..", std::to_string(laser.max_range_mm),
                     " mm"}));
    return f;
}

ScanData run_scan(const ScanSettings& s) {
    ScanData d;
    d.scene_source = s.scene;
    // Everything is checked before the simulation, so a bad input costs nothing and writes
    // nothing.
    scanner::ScannerSpec spec;
    spec.laser = scanner::laser_preset(s.laser);
    spec.readings_per_ray = s.readings;
    spec.optical_offset_m = Vec3d(0, 0, optical_offset_m(s.optical_offset));
    spec.validate();
    const double pose_sigma_m =
        s.pose_error.empty() ? 0.0 : parse_length_m(s.pose_error, "--pose-error");
    if (!(pose_sigma_m >= 0 && pose_sigma_m <= 0.5))
        invalid(cat({"--pose-error ", s.pose_error, " must lie between 0 and 0.5 m"}));
    if (!(s.pose_error_deg >= 0 && s.pose_error_deg <= 10))
        invalid(cat(
            {"--pose-error-angle ", num(s.pose_error_deg), " must lie between 0 and 10 degrees"}));
    const scanner::NoiseModel noise = noise_model(s.noise);
    d.fuse = fuse_options(s.readings, s.trim, s.min_range, s.max_range, spec.laser);
    d.fuse.veil.angle_deg = s.veil_angle_deg;
    scanner::validate(d.fuse.veil);
    d.scene = std::make_unique<scanner::Scene>(load_scene(s.scene));
    d.poses = load_poses(s.poses, d.scene->description().scanner);

    Stopwatch watch;
    const scanner::ScanSimulator simulator(*d.scene, spec, noise);
    for (scanner::SimulatedScan& sim : simulator.simulate(d.poses, s.seed))
        d.raws.push_back(std::move(sim.raw));
    // Scanned from the true poses, fused with the recorded (slightly wrong) ones.
    for (std::size_t k = 0; k < d.raws.size(); ++k) {
        d.raws[k].pose =
            scanner::perturb_pose(d.raws[k].pose, pose_sigma_m,
                                  scanner::deg_to_rad(s.pose_error_deg), mix_seed(~s.seed, k));
        d.poses[k] = d.raws[k].pose;
    }
    d.simulate_seconds = watch.lap();
    d.cloud = scanner::fuse_scans(d.raws, d.fuse, &d.fused);
    d.fuse_seconds = watch.lap();
    return d;
}

std::string raw_scan_name(std::size_t k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "scan-%03zu.sgraw", k);
    return buf;
}

namespace {

// The files a scan folder holds: a new scan replaces them all, so no scan-NNN.sgraw of an earlier
// scan with more poses survives beside the new cloud.
bool is_scan_file(std::string_view name) {
    if (name.starts_with("scan-") && name.ends_with(".sgraw")) return true;
    for (const std::string_view n :
         {"cloud.ply", "truth-faces.json", "scene.json", "poses.txt", "scan.json"})
        if (n == name) return true;
    return false;
}

}  // namespace

void write_scan_outputs(const fs::path& dir, const ScanData& d, const ScanSettings& s) {
    std::vector<std::uint64_t> per_scan(d.raws.size(), 0);
    for (const std::uint32_t k : d.cloud.scan_index) ++per_scan[k];
    nlohmann::json scans = nlohmann::json::array();
    for (std::size_t k = 0; k < d.raws.size(); ++k)
        scans.push_back(
            {{"file", raw_scan_name(k)},
             {"points", per_scan[k]},
             {"mixed_pixels_dropped", k < d.fused.veil_points.size() ? d.fused.veil_points[k] : 0},
             {"pose", io::pose_to_json(d.poses[k])}});
    const scanner::LaserSpec& laser = d.raws.empty() ? scanner::LaserSpec{} : d.raws[0].spec.laser;
    const nlohmann::json manifest = {
        {"format", "surfgrow-scan"},
        {"version", 1},
        {"scene", d.scene->description().name},
        {"scene_source", d.scene_source},
        {"seed", s.seed},
        {"readings_per_ray", s.readings},
        {"trim_q", s.trim},
        {"laser", s.laser},
        {"noise", s.noise},
        {"optical_offset_m", d.raws.empty() ? 0.0 : d.raws[0].spec.optical_offset_m.z()},
        {"range_mm",
         {d.fuse.min_range_mm ? d.fuse.min_range_mm : laser.min_range_mm,
          d.fuse.max_range_mm ? d.fuse.max_range_mm : laser.max_range_mm}},
        {"veil_filter",
         {{"angle_deg", d.fuse.veil.angle_deg}, {"min_step_mm", d.fuse.veil.min_step_mm}}},
        {"points", d.cloud.size()},
        {"scans", scans},
        {"files",
         {{"cloud", "cloud.ply"},
          {"truth_faces", "truth-faces.json"},
          {"scene", "scene.json"},
          {"poses", "poses.txt"}}},
    };

    io::OutputTransaction tx(dir, is_scan_file);
    for (std::size_t k = 0; k < d.raws.size(); ++k)
        tx.add(raw_scan_name(k), [&](std::ostream& o) { o << io::encode_raw_scan(d.raws[k]); });
    tx.add("cloud.ply", [&](std::ostream& o) {
        io::write_ply(o, d.cloud, io::PlyEncoding::kBinaryLittleEndian, true, true);
    });
    tx.add("truth-faces.json", [&](std::ostream& o) { o << io::truth_faces_to_json(*d.scene); });
    tx.add("scene.json", [&](std::ostream& o) { o << io::scene_to_json(d.scene->description()); });
    tx.add("poses.txt", [&](std::ostream& o) { o << io::poses_to_text(d.poses); });
    tx.add("scan.json", [&](std::ostream& o) { o << json_text(manifest); });
    tx.commit();
}

}  // namespace surfgrow::cli
