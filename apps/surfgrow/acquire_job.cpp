#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "acquire_job.hpp"
#include "cli_common.hpp"
#include "exit_status.hpp"
#include "scan_job.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/random.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/emulated_port.hpp"
#include "surfgrow/io/poses_file.hpp"
#include "surfgrow/io/raw_scan_format.hpp"
#include "surfgrow/io/scene_file.hpp"
#include "surfgrow/io/serial_port.hpp"
#include "surfgrow/scanner/acquisition.hpp"
#include "surfgrow/scanner/dynamixel.hpp"
#include "surfgrow/scanner/emulated_rig.hpp"
#include "surfgrow/scanner/scene.hpp"

namespace surfgrow::cli {

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

[[noreturn]] void invalid(const std::string& message) {
    throw Error(ErrorCode::kInvalidParameter, message);
}

// "-60deg:60deg:1/3deg" as a tilt plan: first, then every step up to last (inclusive, within a
// millionth of a step).
scanner::TiltSpec parse_tilt(const std::string& text) {
    const std::size_t a = text.find(':'), b = text.find(':', a == std::string::npos ? a : a + 1);
    if (a == std::string::npos || b == std::string::npos)
        throw Error(
            ErrorCode::kUsage,
            cat({"--tilt: '", text, "' is not FIRST:LAST:STEP (e.g. -60deg:60deg:1/3deg)"}));
    const double first = parse_angle_deg(text.substr(0, a), "--tilt");
    const double last = parse_angle_deg(text.substr(a + 1, b - a - 1), "--tilt");
    const double step = parse_angle_deg(text.substr(b + 1), "--tilt");
    if (!(step > 0) || !(last >= first) || std::abs(first) > 180 || std::abs(last) > 180)
        invalid(cat(
            {"--tilt ", text, ": needs FIRST <= LAST within -180..180 deg and a positive STEP"}));
    const double count = std::floor((last - first) / step + 1e-6) + 1;
    if (count > 20000)
        invalid(cat({"--tilt ", text, ": ", std::to_string(static_cast<long long>(count)),
                     " positions (at most 20000)"}));
    scanner::TiltSpec t;
    t.first_deg = first;
    t.step_deg = step;
    t.positions = static_cast<int>(count);
    t.validate();
    return t;
}

// A whole number after `key=` in a fault, bounded.
int fault_count(std::string_view value, const std::string& fault) {
    int n = -1;
    const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
    if (ec != std::errc() || ptr != value.data() + value.size() || n < 0 || n > 10000000)
        throw Error(ErrorCode::kUsage,
                    cat({"--emulate-fault ", fault, ": expected a count 0..10000000"}));
    return n;
}

// The faults to inject, from "urg-corrupt=N", "urg-drop=N", "urg-unplug=N", "servo-drop=N",
// "servo-lag=ANGLE", "servo-stall=ANGLE" (N counts replies from 0).
void add_fault(const std::string& fault, scanner::UrgFaults& urg,
               scanner::dxl::ServoFaults& servo) {
    const std::size_t eq = fault.find('=');
    const std::string key = fault.substr(0, eq);
    const std::string_view value =
        eq == std::string::npos ? std::string_view() : std::string_view(fault).substr(eq + 1);
    if (key == "urg-corrupt") {
        urg.corrupt.insert(fault_count(value, fault));
    } else if (key == "urg-drop") {
        urg.dropped.insert(fault_count(value, fault));
    } else if (key == "urg-garble") {
        urg.garbled.insert(fault_count(value, fault));
    } else if (key == "servo-corrupt") {
        servo.corrupt.insert(fault_count(value, fault));
    } else if (key == "urg-unplug") {
        urg.unplugged_after = fault_count(value, fault);
    } else if (key == "servo-drop") {
        servo.dropped.insert(fault_count(value, fault));
    } else if (key == "servo-lag" || key == "servo-stall") {
        const double deg = parse_angle_deg(value, "--emulate-fault " + key);
        if (!(std::abs(deg) <= 90)) invalid(cat({"--emulate-fault ", fault, ": within 90 deg"}));
        if (key == "servo-lag")
            servo.lag_ticks = static_cast<std::int32_t>(std::lround(deg * 4096 / 360));
        else
            servo.stall_at = scanner::dxl::ticks_of(deg);
    } else {
        throw Error(ErrorCode::kUsage,
                    cat({"--emulate-fault ", fault,
                         ": unknown fault (urg-corrupt=N, urg-drop=N, urg-garble=N, urg-unplug=N, "
                         "servo-corrupt=N, servo-drop=N, servo-lag=ANGLE, servo-stall=ANGLE)"}));
    }
}

// Where the scan goes: a .sgraw file as named, or the next free scan-NNN.sgraw in a folder (so
// scans acquired one after another fuse in their order with `scan2cloud DIR`).
fs::path output_file(const std::string& out) {
    if (fs::path(out).extension() == ".sgraw") {
        // Checked before the scan, which takes minutes with the real device.
        const fs::path parent = fs::path(out).parent_path();
        std::error_code ec;
        if (!parent.empty() && !fs::is_directory(parent, ec))
            throw Error(ErrorCode::kCannotWrite,
                        cat({out, ": its folder does not exist (nothing was scanned)"}));
        return out;
    }
    std::error_code ec;
    fs::create_directories(out, ec);
    if (!fs::is_directory(out))
        throw Error(ErrorCode::kCannotWrite,
                    cat({out, ": not a folder and not a .sgraw file (", ec.message(), ")"}));
    for (std::size_t k = 0; k < 100000; ++k) {
        const fs::path p = fs::path(out) / raw_scan_name(k);
        if (!fs::exists(p)) return p;
    }
    throw Error(ErrorCode::kCannotWrite, cat({out, ": 100000 scans already"}));
}

// The pose: a poses file holding one, or with --emulate "k/N", pose k of N along the scene's
// scan path (as `surfgrow scan --poses N` takes them; `index` becomes k).
scanner::Pose load_pose(const std::string& text, const scanner::SceneDescription* scene,
                        int& index) {
    const std::size_t slash = text.find('/');
    int k = -1, n = -1;
    if (scene != nullptr && slash != std::string::npos && slash > 0 &&
        std::from_chars(text.data(), text.data() + slash, k).ptr == text.data() + slash &&
        std::from_chars(text.data() + slash + 1, text.data() + text.size(), n).ptr ==
            text.data() + text.size()) {
        if (!(n >= 1 && n <= 1000 && k >= 0 && k < n))
            invalid(cat({"--pose ", text, ": K/N needs 0 <= K < N <= 1000"}));
        index = k;
        return scanner::scan_poses(scene->scanner, n)[static_cast<std::size_t>(k)];
    }
    const std::vector<scanner::Pose> poses = io::read_poses_file(text);
    if (poses.size() != 1)
        invalid(
            cat({text, ": ", std::to_string(poses.size()), " poses; a scan is taken from one"}));
    return poses.front();
}

std::string utc_now() {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

}  // namespace

void AcquireSettings::add_to(CLI::App& cmd) {
    cmd.add_option("-o,--out", out,
                   "A .sgraw file, or a folder: the scan becomes its next scan-NNN.sgraw")
        ->required();
    cmd.add_option("--port", port, "The URG's port (USB: /dev/ttyACM*)")->capture_default_str();
    cmd.add_option("--baud", baud, "The URG's serial speed (ignored over USB)")
        ->capture_default_str();
    cmd.add_option("--servo-port", servo_port, "The servo's port (a USB-RS485 adapter)")
        ->capture_default_str();
    cmd.add_option("--servo-baud", servo_baud, "The servo's bus speed")->capture_default_str();
    cmd.add_option("--servo-id", servo_id, "The servo's DYNAMIXEL id (0..252)")
        ->capture_default_str();
    cmd.add_option("--tilt", tilt, "Tilt plan FIRST:LAST:STEP (angles with deg or rad)")
        ->capture_default_str();
    cmd.add_option("--readings", readings, "Readings per ray, n of eq. (1)")->capture_default_str();
    cmd.add_option("--optical-offset", optical_offset,
                   "Laser optical centre above the tilt axis (measure it, or surfgrow calibrate)")
        ->capture_default_str();
    cmd.add_option("--pose", pose,
                   "Sensor-to-world pose: a poses file holding one pose (default: identity); "
                   "with --emulate also K/N, pose K of N along the scene's scan path (default "
                   "0/1)");
    cmd.add_option("--timeout", timeout, "Wait this long for a reply (e.g. 500ms)")
        ->capture_default_str();
    cmd.add_option("--attempts", attempts,
                   "Send a command this often before the device counts as failed (1..20)")
        ->capture_default_str();
    cmd.add_option("--emulate", emulate,
                   "Emulate both devices scanning this built-in scene or scene file, behind "
                   "pseudo-terminals (the ports above are then not used)");
    cmd.add_option("--emulate-fault", faults,
                   "With --emulate: urg-corrupt=N, urg-drop=N, urg-garble=N, urg-unplug=N, "
                   "servo-corrupt=N, servo-drop=N (replies counted from 0), servo-lag=ANGLE, "
                   "servo-stall=ANGLE; repeatable");
    cmd.add_option("--noise", noise, "With --emulate: datasheet or ideal")->capture_default_str();
    cmd.add_option("--emulate-offset", true_offset,
                   "With --emulate: the laser's true optical offset, when --optical-offset is "
                   "wrong (default: --optical-offset)");
    cmd.add_option("--emulate-zero", true_zero,
                   "With --emulate: the laser's true tilt when the servo reads 0 (a turned horn)")
        ->capture_default_str();
    add_seed_option(cmd, seed, "With --emulate: seed of the simulated noise");
}

AcquiredScan take_scan(const AcquireSettings& a) {
    // Every argument checked before a device is touched.
    scanner::ScannerSpec spec;
    spec.laser = scanner::urg04lx_scip_682();
    spec.tilt = parse_tilt(a.tilt);
    spec.readings_per_ray = a.readings;
    spec.optical_offset_m = Vec3d(0, 0, optical_offset_m(a.optical_offset));
    spec.validate();
    if (a.servo_id < 0 || a.servo_id > 252)
        invalid(cat({"--servo-id ", std::to_string(a.servo_id), ": 0..252"}));
    if (a.attempts < 1 || a.attempts > 20)
        invalid(cat({"--attempts ", std::to_string(a.attempts), ": 1..20"}));
    const std::chrono::milliseconds timeout = parse_duration(a.timeout, "--timeout", 10, 60000);
    scanner::UrgFaults urg_faults;
    scanner::dxl::ServoFaults servo_faults;
    if (!a.faults.empty() && a.emulate.empty())
        throw Error(ErrorCode::kUsage, "--emulate-fault needs --emulate");
    for (const std::string& f : a.faults) add_fault(f, urg_faults, servo_faults);
    if (a.emulate.empty() && (!a.true_offset.empty() || a.true_zero != "0deg"))
        throw Error(ErrorCode::kUsage, "--emulate-offset and --emulate-zero need --emulate");
    const double true_offset_m =
        a.true_offset.empty() ? spec.optical_offset_m.z() : optical_offset_m(a.true_offset);
    const double true_zero_deg = parse_angle_deg(a.true_zero, "--emulate-zero");
    if (!(std::abs(true_zero_deg) <= 10))
        invalid(cat({"--emulate-zero ", a.true_zero, ": within 10 deg"}));
    const auto servo_id = static_cast<std::uint8_t>(a.servo_id);

    std::optional<scanner::Scene> scene;
    if (!a.emulate.empty()) scene.emplace(load_scene(a.emulate));
    int pose_index = 0;
    const scanner::Pose pose =
        !a.pose.empty()     ? load_pose(a.pose, scene ? &scene->description() : nullptr, pose_index)
        : scene.has_value() ? scene->description().scanner.home
                            : scanner::Pose::Identity();
    const fs::path file = output_file(a.out);

    // The devices: the emulated rig behind two pseudo-terminals, or the real ports.
    std::unique_ptr<scanner::EmulatedRig> rig;
    std::unique_ptr<io::EmulatedPort> urg_pty, servo_pty;
    std::string urg_path = a.port, servo_path = a.servo_port;
    if (scene) {
        scanner::RigSetup setup;
        setup.noise = noise_model(a.noise);
        setup.pose = pose;
        setup.seed = mix_seed(a.seed, static_cast<std::uint64_t>(pose_index));
        setup.urg_faults = urg_faults;
        setup.servo_faults = servo_faults;
        setup.servo_id = servo_id;
        setup.tilt_zero_deg = true_zero_deg;
        scanner::ScannerSpec truth = spec;
        truth.optical_offset_m.z() = true_offset_m;
        rig = std::make_unique<scanner::EmulatedRig>(*scene, truth, setup);
        urg_pty = std::make_unique<io::EmulatedPort>(
            [r = rig.get()](std::string_view l) { return r->urg_reply(l); });
        servo_pty = std::make_unique<io::EmulatedPort>(
            [r = rig.get()](std::string_view p) { return r->servo_reply(p); },
            scanner::dxl::packet_end);
        urg_path = urg_pty->path().string();
        servo_path = servo_pty->path().string();
    }
    io::SerialPort urg_port(urg_path, a.baud, timeout);
    io::SerialPort servo_port(servo_path, a.servo_baud, timeout, scanner::dxl::packet_end);
    // A port failing (the device unplugged) is the device failing: one kind of error.
    const auto through = [](io::SerialPort& port) {
        return [&port](std::string_view bytes) {
            try {
                return port.exchange(bytes);
            } catch (const Error& e) {
                throw scanner::DeviceError(e.what());
            }
        };
    };
    scanner::UrgDriver urg(through(urg_port), a.attempts);
    scanner::dxl::ServoDriver servo(through(servo_port), servo_id, a.attempts);

    const bool progress = !a.quiet && stderr_is_terminal();
    const auto started = std::chrono::steady_clock::now();
    scanner::RawScan scan;
    try {
        scan = scanner::acquire_scan(urg, servo, spec, pose, [progress](int done, int planned) {
            if (progress) std::fprintf(stderr, "\racquire: %d/%d tilt positions", done, planned);
        });
    } catch (const std::runtime_error& e) {  // DeviceError, ServoError
        if (progress) std::fputc('\n', stderr);
        throw OutcomeError(Outcome::kDeviceFailed,
                           cat({"acquire: ", e.what(), "; nothing was written"}));
    }
    if (progress) std::fputc('\n', stderr);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (rig) {  // ground truth per ray, from the sweeps the rig cast at each angle read back
        scan.note += cat({"\nemulated: scene ", a.emulate, ", seed ", std::to_string(a.seed)});
        for (const double deg : scan.tilt_read_deg) {
            const std::vector<std::int32_t> t = rig->truth_at(deg);
            scan.truth_face_id.insert(scan.truth_face_id.end(), t.begin(), t.end());
        }
    } else {
        scan.note += cat({"\nstarted: ", utc_now()});
    }
    io::write_raw_scan(file, scan);
    // Beside emulated scans, their scene: `eval --truth DIR` scores a result against it.
    if (rig && file.parent_path() != fs::path() && fs::path(a.out).extension() != ".sgraw")
        io::write_scene_file(file.parent_path() / "scene.json", scene->description());
    if (scan.partial())
        throw OutcomeError(
            Outcome::kDeviceFailed,
            cat({"acquire: ", scan.stop_reason, "; the partial scan (",
                 std::to_string(scan.spec.tilt.positions), " of ",
                 std::to_string(scan.planned_positions), " tilt positions) is in ", file.string(),
                 ", marked partial (scan2cloud --allow-partial uses it)"}));
    AcquiredScan taken;
    taken.file = file;
    taken.scan = std::move(scan);
    taken.seconds = seconds;
    taken.retries = urg.retries();
    return taken;
}

}  // namespace surfgrow::cli
