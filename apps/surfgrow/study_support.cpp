#include "study_support.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli_common.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"

extern char** environ;

namespace surfgrow::cli {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void usage(std::string_view option, std::initializer_list<std::string_view> what) {
    std::string message = cat({option, ": "});
    for (auto w : what) message.append(w);
    throw Error(ErrorCode::kUsage, message);
}

[[noreturn]] void invalid(std::string_view option, std::initializer_list<std::string_view> what) {
    std::string message = cat({option, ": "});
    for (auto w : what) message.append(w);
    throw Error(ErrorCode::kInvalidParameter, message);
}

std::vector<std::string_view> split(std::string_view text, char sep) {
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t at = text.find(sep, start);
        parts.push_back(trim(text.substr(start, at == std::string_view::npos ? at : at - start)));
        if (at == std::string_view::npos) break;
        start = at + 1;
    }
    return parts;
}

// "a:b" into its two ends; false when there is no ':'.
bool split_range(std::string_view text, std::string_view option, std::string_view& a,
                 std::string_view& b) {
    const std::size_t colon = text.find(':');
    if (colon == std::string_view::npos) return false;
    if (text.find(':', colon + 1) != std::string_view::npos ||
        text.find(',') != std::string_view::npos)
        usage(option, {"'", text, "' is neither a range FROM:TO nor a list A,B,C"});
    a = trim(text.substr(0, colon));
    b = trim(text.substr(colon + 1));
    return true;
}

void check_steps(int steps, std::string_view option) {
    if (steps < 2 || steps > kMaxSweepValues)
        invalid(option, {"a range needs between 2 and ", std::to_string(kMaxSweepValues),
                         " steps, got ", std::to_string(steps)});
}

void check_list_size(std::size_t n, std::string_view option) {
    if (n > static_cast<std::size_t>(kMaxSweepValues))
        invalid(option,
                {"at most ", std::to_string(kMaxSweepValues), " values, got ", std::to_string(n)});
}

// The value rounded to `digits` significant digits, through its decimal text, so that it prints
// back as that text ("0.00143", not "0.0014299999999999998").
double round_significant(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*e", digits - 1, v);
    double out = v;
    std::from_chars(buf, buf + std::strlen(buf), out);
    return out;
}

template <typename T>
void sort_unique(std::vector<T>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
}

int parse_int(std::string_view text, std::string_view option) {
    int value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end)
        usage(option, {"'", text, "' is not a whole number"});
    return value;
}

std::uint64_t parse_size(std::string_view text, std::string_view option) {
    double value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || !std::isfinite(value))
        usage(option, {"'", text, "' is not a point count (e.g. 50000, 50k, 1M)"});
    const std::string_view suffix(ptr, static_cast<std::size_t>(end - ptr));
    if (suffix == "k")
        value *= 1e3;
    else if (suffix == "M")
        value *= 1e6;
    else if (!suffix.empty())
        usage(option, {"'", text, "': unknown suffix '", suffix, "' (use k or M)"});
    if (!(value >= 0) || value > 1e15 || value != std::floor(value))
        invalid(option, {"'", text, "' is not a whole, positive point count"});
    return static_cast<std::uint64_t>(value);
}

}  // namespace

std::vector<double> parse_length_sweep(std::string_view text, std::string_view option, int steps) {
    text = trim(text);
    std::vector<double> values;
    auto positive = [&](double v, std::string_view what) {
        if (!(v > 0)) invalid(option, {"'", what, "' is not a positive length"});
        return v;
    };
    std::string_view a, b;
    if (split_range(text, option, a, b)) {
        const double lo = positive(parse_length_m(a, option), a);
        const double hi = positive(parse_length_m(b, option), b);
        if (!(hi > lo))
            invalid(option, {"the range ", text, " must increase (FROM:TO with FROM < TO)"});
        check_steps(steps, "--steps");
        values.push_back(lo);
        for (int i = 1; i + 1 < steps; ++i) {
            const double t = double(i) / double(steps - 1);
            values.push_back(round_significant(lo * std::pow(hi / lo, t), 3));
        }
        values.push_back(hi);
    } else {
        for (const std::string_view part : split(text, ','))
            values.push_back(positive(parse_length_m(part, option), part));
        check_list_size(values.size(), option);
    }
    sort_unique(values);
    return values;
}

std::vector<int> parse_count_sweep(std::string_view text, std::string_view option, int steps,
                                   int lo, int hi) {
    text = trim(text);
    std::vector<int> values;
    auto in_range = [&](int v) {
        if (v < lo || v > hi)
            invalid(option, {std::to_string(v), " is outside ", std::to_string(lo), "..",
                             std::to_string(hi)});
        return v;
    };
    std::string_view a, b;
    if (split_range(text, option, a, b)) {
        const int from = in_range(parse_int(a, option));
        const int to = in_range(parse_int(b, option));
        if (!(to > from))
            invalid(option, {"the range ", text, " must increase (FROM:TO with FROM < TO)"});
        check_steps(steps, option == "--min-pts" ? "--min-pts-steps" : "--steps");
        for (int i = 0; i < steps; ++i)
            values.push_back(static_cast<int>(
                std::lround(from + double(to - from) * double(i) / double(steps - 1))));
    } else {
        for (const std::string_view part : split(text, ','))
            values.push_back(in_range(parse_int(part, option)));
        check_list_size(values.size(), option);
    }
    sort_unique(values);
    return values;
}

std::vector<std::uint64_t> parse_size_sweep(std::string_view text, std::string_view option,
                                            int steps, std::uint64_t lo, std::uint64_t hi) {
    text = trim(text);
    std::vector<std::uint64_t> values;
    auto in_range = [&](std::uint64_t v) {
        if (v < lo || v > hi)
            invalid(option, {std::to_string(v), " points is outside ", std::to_string(lo), "..",
                             std::to_string(hi)});
        return v;
    };
    std::string_view a, b;
    if (split_range(text, option, a, b)) {
        const std::uint64_t from = in_range(parse_size(a, option));
        const std::uint64_t to = in_range(parse_size(b, option));
        if (!(to > from))
            invalid(option, {"the range ", text, " must increase (FROM:TO with FROM < TO)"});
        check_steps(steps, "--steps");
        values.push_back(from);
        for (int i = 1; i + 1 < steps; ++i) {
            const double t = double(i) / double(steps - 1);
            values.push_back(static_cast<std::uint64_t>(
                round_significant(double(from) * std::pow(double(to) / double(from), t), 2)));
        }
        values.push_back(to);
    } else {
        for (const std::string_view part : split(text, ','))
            values.push_back(in_range(parse_size(part, option)));
        check_list_size(values.size(), option);
    }
    sort_unique(values);
    return values;
}

void check_count(int value, std::string_view option, int hi) {
    if (value < 1 || value > hi)
        invalid(option,
                {"must be between 1 and ", std::to_string(hi), ", got ", std::to_string(value)});
}

std::string CsvTable::text() const {
    std::string out;
    auto line = [&](const std::vector<std::string>& fields) {
        for (std::size_t i = 0; i < fields.size(); ++i) {
            if (i) out += ',';
            out += fields[i];
        }
        out += '\n';
    };
    line(header);
    for (const auto& row : rows) line(row);
    return out;
}

std::string fixed(double value, int decimals) {
    if (!std::isfinite(value)) return "";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return buf;
}

std::vector<std::string> result_columns(bool truth) {
    std::vector<std::string> c = {"points", "surfaces", "registered_pct", "registered_grown_pct",
                                  "reduction"};
    if (truth) {
        c.emplace_back("normal_err_median_deg");
        c.emplace_back("normal_err_p95_deg");
    }
    return c;
}

std::vector<std::string> timing_columns() {
    return {"seconds", "index_s", "grow_s", "attach_s", "finish_s"};
}

std::vector<std::string> result_fields(const GrowStats& s,
                                       const std::pair<double, double>* normal_deg) {
    std::vector<std::string> f = {std::to_string(s.valid_points), std::to_string(s.surfaces),
                                  fixed(100.0 * s.registered_fraction(), 3),
                                  fixed(100.0 * s.registered_grown_fraction(), 3),
                                  fixed(s.data_reduction(), 3)};
    if (normal_deg) {
        f.push_back(fixed(normal_deg->first, 4));
        f.push_back(fixed(normal_deg->second, 4));
    }
    return f;
}

std::vector<std::string> timing_fields(const StageTimes& t) {
    return {fixed(t.total(), 6), fixed(t.index, 6), fixed(t.grow, 6), fixed(t.attach, 6),
            fixed(t.finish, 6)};
}

StageTimes median_run(const std::vector<StageTimes>& runs) {
    if (runs.empty()) return {};
    std::vector<StageTimes> sorted = runs;
    std::sort(sorted.begin(), sorted.end(),
              [](const StageTimes& x, const StageTimes& y) { return x.total() < y.total(); });
    return sorted[(sorted.size() - 1) / 2];
}

// ------------------------------------------------------------------------------------------------
// Plots

namespace {

constexpr const char* kPlotScript = "surfgrow_plots.py";

// A temporary folder, removed with everything in it when this goes out of scope.
class TempFolder {
  public:
    TempFolder() {
        std::error_code ec;
        fs::path base = fs::temp_directory_path(ec);
        if (ec) base = "/tmp";
        std::string pattern = (base / "surfgrow-plots-XXXXXX").string();
        if (::mkdtemp(pattern.data())) path_ = pattern;
    }
    ~TempFolder() {
        if (path_.empty()) return;
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    [[nodiscard]] const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

// The plot script, or an empty path with the reason in `why`.
fs::path find_plot_script(std::string& why) {
    if (const char* dir = std::getenv("SURFGROW_PLOT_SCRIPT_DIR"); dir && *dir) {
        const fs::path script = fs::path(dir) / kPlotScript;
        if (fs::is_regular_file(script)) return script;
        why = cat({kPlotScript, " is not in SURFGROW_PLOT_SCRIPT_DIR=", dir});
        return {};
    }
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path installed =
            exe.parent_path().parent_path() / "share" / "surfgrow" / "plots" / kPlotScript;
        if (fs::is_regular_file(installed, ec)) return installed;
    }
#ifdef SURFGROW_PLOT_SCRIPT_DIR
    const fs::path source = fs::path(SURFGROW_PLOT_SCRIPT_DIR) / kPlotScript;
    if (fs::is_regular_file(source, ec)) return source;
#endif
    why = cat({kPlotScript,
               " not found (looked in <binary>/../share/surfgrow/plots and the source tree's "
               "scripts/plots; set SURFGROW_PLOT_SCRIPT_DIR)"});
    return {};
}

std::string read_file(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The last non-empty line of a log, for a one-line warning.
std::string last_line(const std::string& log) {
    std::size_t end = log.find_last_not_of(" \t\r\n");
    if (end == std::string::npos) return "";
    const std::size_t start = log.rfind('\n', end);
    return log.substr(start == std::string::npos ? 0 : start + 1,
                      end - (start == std::string::npos ? 0 : start + 1) + 1);
}

}  // namespace

Plots draw_plots(std::string_view kind,
                 const std::vector<std::pair<std::string, std::string>>& csv_files,
                 const std::vector<std::string>& png_names, const std::string& title) {
    Plots plots;
    const fs::path script = find_plot_script(plots.why_not);
    if (script.empty()) return plots;
    const char* python_env = std::getenv("SURFGROW_PYTHON");
    const std::string python = python_env && *python_env ? python_env : "/usr/bin/python3";

    const TempFolder tmp;
    if (tmp.path().empty()) {
        plots.why_not = "cannot create a temporary folder";
        return plots;
    }
    for (const auto& [name, bytes] : csv_files) {
        std::ofstream out(tmp.path() / name, std::ios::binary);
        out << bytes;
        if (!out) {
            plots.why_not = cat({"cannot write ", (tmp.path() / name).string()});
            return plots;
        }
    }

    const std::string log_file = (tmp.path() / "plot.log").string();
    const std::string script_s = script.string(), kind_s(kind), folder_s = tmp.path().string();
    std::vector<std::string> args = {python, script_s, kind_s, folder_s, "--title", title};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0600);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t pid = 0;
    const int spawned =
        ::posix_spawn(&pid, python.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
        plots.why_not = cat({"cannot run ", python, ": ", std::strerror(spawned)});
        return plots;
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            plots.why_not = cat({"lost the plot process: ", std::strerror(errno)});
            return plots;
        }
    }
    const std::string log = read_file(log_file);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        const std::string said = last_line(log);
        plots.why_not = code == 127 ? cat({"cannot run ", python})
                                    : cat({python, " ", script_s, " failed",
                                           code >= 0 ? cat({" (exit ", std::to_string(code), ")"})
                                                     : std::string(" (killed by a signal)"),
                                           said.empty() ? "" : ": ", said});
        return plots;
    }
    for (const std::string& name : png_names) {
        const fs::path png = tmp.path() / name;
        std::string bytes = fs::is_regular_file(png) ? read_file(png) : std::string();
        if (bytes.size() < 8 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) {
            plots.why_not = cat({script_s, " did not draw ", name});
            plots.files.clear();
            return plots;
        }
        plots.files.emplace_back(name, std::move(bytes));
    }
    plots.drawn = true;
    return plots;
}

void publish_study(const std::filesystem::path& out,
                   const std::vector<std::pair<std::string, std::string>>& csv_files,
                   const Plots& plots, const std::string& record_name, const nlohmann::json& record,
                   std::string_view written) {
    // A new study or sweep replaces the earlier one's tables, plots and record as a whole.
    io::OutputTransaction tx(out, [&](std::string_view name) {
        return name == record_name || name.ends_with(".csv") || name.ends_with(".png");
    });
    // (Not structured bindings: clang 14 cannot capture them in a lambda.)
    for (const auto& file : csv_files)
        tx.add(file.first, [&](std::ostream& o) { o << file.second; });
    for (const auto& file : plots.files)
        tx.add(file.first, [&](std::ostream& o) { o << file.second; });
    tx.add(record_name, [&](std::ostream& o) { o << record.dump(2) << "\n"; });
    tx.commit();
    if (!plots.drawn)
        std::cerr << "surfgrow: warning: plots skipped: " << plots.why_not << "\n         "
                  << written
                  << " written; install Debian's python3-matplotlib, or pass --require-plots to "
                     "make this an error"
                  << std::endl;
}

}  // namespace surfgrow::cli
