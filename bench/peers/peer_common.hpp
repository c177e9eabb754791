// What every benchmark program shares: arguments, clocks, memory, and the result files.
//
// Each tool (surfgrow and its peers) reads one cloud and writes into --out DIR:
//   result.json  tool, method, parameters, seconds (io, algorithm per repeat), memory, counts
//   labels.i32   one little-endian int32 per input point: its segment id, or -1
//   planes.f64   one row of 4 little-endian doubles (nx ny nz d, n.x + d = 0) per segment id
// The driver (run_peers.py) computes every metric from these files, the same way for all tools.
#pragma once

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace peers {

/// `--key value` pairs (and bare `--flag`s, stored as "1") after the positional input path.
class Args {
  public:
    Args(int argc, char** argv) {
        for (int i = 1; i < argc; ++i) {
            const std::string_view a = argv[i];
            if (!a.starts_with("--")) {
                positional_.emplace_back(a);
            } else if (i + 1 < argc && !std::string_view(argv[i + 1]).starts_with("--")) {
                kv_.insert_or_assign(std::string(a.substr(2)), std::string(argv[++i]));
            } else {
                kv_.insert_or_assign(std::string(a.substr(2)), std::string(1, '1'));
            }
        }
    }
    [[nodiscard]] std::string input() const {
        if (positional_.empty()) throw std::runtime_error("missing input cloud");
        return positional_.front();
    }
    [[nodiscard]] bool has(const std::string& k) const { return kv_.count(k) != 0; }
    [[nodiscard]] std::string str(const std::string& k, const std::string& def) const {
        const auto it = kv_.find(k);
        return it == kv_.end() ? def : it->second;
    }
    [[nodiscard]] double num(const std::string& k, double def) const {
        const auto it = kv_.find(k);
        return it == kv_.end() ? def : std::stod(it->second);
    }
    [[nodiscard]] int integer(const std::string& k, int def) const {
        return static_cast<int>(num(k, def));
    }

  private:
    std::vector<std::string> positional_;
    std::map<std::string, std::string> kv_;
};

inline double now_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

/// getrusage's ru_maxrss, bytes: includes the pre-exec memory of the process that spawned us.
inline double ru_maxrss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) * 1024.0;
}

/// A field of /proc/self/status in kB (VmRSS, VmHWM), as bytes; 0 if unreadable.
inline double proc_status_bytes(const char* field) {
    std::ifstream f("/proc/self/status");
    std::string line;
    const std::string key = std::string(field) + ":";
    while (std::getline(f, line)) {
        if (line.rfind(key, 0) == 0) return std::atof(line.c_str() + key.size()) * 1024.0;
    }
    return 0.0;
}

/// The high-water mark before the last reset_peak_rss(), bytes.
inline double& hwm_before_reset() {
    static double v = 0.0;
    return v;
}

/// Resets the peak-RSS high-water mark (VmHWM) to the current RSS, so the peak of the algorithm
/// alone can be read afterwards; false where the kernel refuses.
inline bool reset_peak_rss() {
    hwm_before_reset() = proc_status_bytes("VmHWM");
    std::ofstream f("/proc/self/clear_refs");
    if (!f) return false;
    f << "5";
    f.flush();
    return static_cast<bool>(f);
}

/// Peak resident set of this process, bytes: VmHWM, not getrusage's ru_maxrss, which also
/// counts the parent's memory from before exec (a Python driver's arrays would show up in it).
inline double process_peak_rss_bytes() {
    return std::max(hwm_before_reset(), proc_status_bytes("VmHWM"));
}

/// CPU seconds (user + system, all threads) this process has used so far.
inline double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// Runs `algorithm` at least once and again while the total stays under `min_seconds`, at most
/// `max_repeats` times; returns each run's wall-clock seconds and appends its CPU seconds to
/// `cpu`. `algorithm(run)` must keep the first run's result (run == 0) and may discard the others.
/// CPU time is reported beside wall time because a loaded machine stretches wall time only.
inline std::vector<double> repeat_timed(const std::function<void(int)>& algorithm,
                                        double min_seconds, int max_repeats,
                                        std::vector<double>& cpu) {
    std::vector<double> times;
    double total = 0.0;
    do {
        const double c0 = cpu_seconds();
        const double t0 = now_s();
        algorithm(static_cast<int>(times.size()));
        times.push_back(now_s() - t0);
        cpu.push_back(cpu_seconds() - c0);
        total += times.back();
    } while (total < min_seconds && static_cast<int>(times.size()) < max_repeats);
    return times;
}

inline double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

template <class T>
void write_binary(const std::string& path, const std::vector<T>& v) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + path);
    const std::size_t n = v.empty() ? 0 : std::fwrite(v.data(), sizeof(T), v.size(), f);
    if (std::fclose(f) != 0 || n != v.size()) throw std::runtime_error("cannot write " + path);
}

/// Everything a tool reports besides the two binary files.
struct Report {
    std::string tool;    ///< "surfgrow", "pcl", "cgal"
    std::string method;  ///< "grow", "region-growing", "ransac", ...
    std::string input;
    std::size_t points = 0;
    double io_seconds = 0.0;
    std::vector<double> algorithm_seconds;      ///< one per repeat; the first run's result is kept
    std::vector<double> algorithm_cpu_seconds;  ///< CPU seconds (all threads) of each repeat
    std::map<std::string, double> stage_seconds;  ///< first run, when the tool has stages
    double baseline_rss = 0.0;                    ///< RSS before reading the input, bytes
    double input_rss = 0.0;                       ///< RSS after reading the input, bytes
    double algorithm_peak_rss = 0.0;  ///< VmHWM during the algorithm (reset before), bytes
    bool algorithm_peak_valid = false;
    std::size_t segments = 0;
    int threads = 1;
    std::map<std::string, double> params;
    std::map<std::string, std::string> notes;
};

inline std::string json_escape(const std::string& s) {
    std::string o;
    for (const char c : s) {
        if (c == '"' || c == '\\') o += '\\';
        if (static_cast<unsigned char>(c) < 0x20) continue;
        o += c;
    }
    return o;
}

/// Writes result.json (no JSON library needed by the peers' programs).
inline void write_report(const std::string& path, const Report& r) {
    std::ofstream f(path);
    auto num = [](double v) {
        char b[64];
        std::snprintf(b, sizeof b, "%.9g", v);
        return std::string(b);
    };
    f << "{\n  \"tool\": \"" << json_escape(r.tool) << "\",\n  \"method\": \""
      << json_escape(r.method) << "\",\n  \"input\": \"" << json_escape(r.input)
      << "\",\n  \"points\": " << r.points << ",\n  \"threads\": " << r.threads
      << ",\n  \"segments\": " << r.segments << ",\n  \"io_seconds\": " << num(r.io_seconds)
      << ",\n  \"algorithm_seconds\": [";
    for (std::size_t i = 0; i < r.algorithm_seconds.size(); ++i)
        f << (i ? ", " : "") << num(r.algorithm_seconds[i]);
    f << "],\n  \"algorithm_seconds_median\": " << num(median(r.algorithm_seconds))
      << ",\n  \"algorithm_cpu_seconds_median\": " << num(median(r.algorithm_cpu_seconds))
      << ",\n  \"stage_seconds\": {";
    bool first = true;
    for (const auto& [k, v] : r.stage_seconds) {
        f << (first ? "" : ", ") << "\"" << json_escape(k) << "\": " << num(v);
        first = false;
    }
    f << "},\n  \"process_peak_rss_bytes\": " << num(process_peak_rss_bytes())
      << ",\n  \"ru_maxrss_bytes\": " << num(ru_maxrss_bytes())
      << ",\n  \"baseline_rss_bytes\": " << num(r.baseline_rss)
      << ",\n  \"input_rss_bytes\": " << num(r.input_rss) << ",\n  \"algorithm_peak_rss_bytes\": "
      << (r.algorithm_peak_valid ? num(r.algorithm_peak_rss) : std::string("null"))
      << ",\n  \"params\": {";
    first = true;
    for (const auto& [k, v] : r.params) {
        f << (first ? "" : ", ") << "\"" << json_escape(k) << "\": " << num(v);
        first = false;
    }
    f << "},\n  \"notes\": {";
    first = true;
    for (const auto& [k, v] : r.notes) {
        f << (first ? "" : ", ") << "\"" << json_escape(k) << "\": \"" << json_escape(v) << "\"";
        first = false;
    }
    f << "}\n}\n";
    if (!f) throw std::runtime_error("cannot write " + path);
}

}  // namespace peers
