// `surfgrow sweep CLOUD --mu 1mm:50mm --min-pts 3:40 -o sweep/`: the paper's parameter study
// (section 5.1, Fig. 5). Grows one cloud over a range of mu and a range of min_pts, the other held
// fixed, and writes time, surfaces and registered % (and, with ground truth, normal error) per
// value as CSV and plots, so that mu can be chosen from evidence.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "eval_job.hpp"
#include "grow_options.hpp"
#include "study_support.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/version.hpp"

namespace surfgrow::cli {

namespace {

namespace fs = std::filesystem;

struct SweepArgs {
    std::string input;
    std::string out = "sweep";
    std::string mu;       // empty: not swept (both empty: both at their defaults)
    std::string min_pts;  // empty: not swept
    int steps = 12;
    int min_pts_steps = 10;
    int repeat = 1;
    GrowOptions grow;  // --at-mu, --at-min-pts and everything `grow` takes
    bool require_plots = false;
    bool quiet = false;
};

// One swept parameter: its name in files, its values and one configuration per value.
struct Sweep {
    std::string name;                 // "mu" or "min_pts"
    std::vector<std::string> values;  // the CSV's first column, formatted
    std::string fixed;                // the other parameter's value, formatted (mu in metres)
    std::vector<GrowerConfig> configs;
};

// The cloud file: CLOUD itself, or CLOUD/cloud.ply when CLOUD is a scan folder.
fs::path cloud_file(const std::string& input) {
    const fs::path p(input);
    std::error_code ec;
    if (fs::is_directory(p, ec)) return p / "cloud.ply";
    return p;
}

// Normal error of one result against the truth: median and p95, degrees.
std::pair<double, double> normal_error(const PointCloud& cloud, const GrowResult& result,
                                       const std::vector<scanner::Face>& faces) {
    const eval::EvalReport report = eval::evaluate(cloud, result, faces);
    return {report.normal_deg.median, report.normal_deg.p95};
}

// Grows with every configuration of `sweep` and tabulates the results.
CsvTable run_sweep(const Sweep& sweep, const PointCloud& cloud, int repeat,
                   const std::vector<scanner::Face>* faces, std::size_t& runs_done,
                   std::size_t runs_total) {
    const bool is_mu = sweep.name == "mu";
    CsvTable table;
    table.header = {is_mu ? "mu_m" : "min_pts", is_mu ? "min_pts" : "mu_m"};
    for (std::string& c : result_columns(faces != nullptr)) table.header.push_back(std::move(c));
    for (std::string& c : timing_columns()) table.header.push_back(std::move(c));
    const bool progress = stderr_is_terminal();
    for (std::size_t i = 0; i < sweep.configs.size(); ++i) {
        const GrowerConfig& config = sweep.configs[i];
        std::vector<StageTimes> times;
        GrowResult result;
        for (int r = 0; r < repeat; ++r) {
            if (progress) {
                std::fprintf(stderr, "\rsweep %-7s %3zu/%zu  %-12s", sweep.name.c_str(),
                             runs_done + 1, runs_total, sweep.values[i].c_str());
                std::fflush(stderr);
            }
            result = grow_surfaces(cloud, config);
            times.push_back(result.stats.seconds);
            ++runs_done;
        }
        std::optional<std::pair<double, double>> normal;
        if (faces) normal = normal_error(cloud, result, *faces);

        std::vector<std::string> row = {sweep.values[i],
                                        is_mu ? std::to_string(config.min_pts) : sweep.fixed};
        for (std::string& f : result_fields(result.stats, normal ? &*normal : nullptr))
            row.push_back(std::move(f));
        for (std::string& f : timing_fields(median_run(times))) row.push_back(std::move(f));
        table.rows.push_back(std::move(row));
    }
    if (progress) std::fprintf(stderr, "\r%60s\r", "");
    return table;
}

void run(const SweepArgs& a) {
    // Every option is checked before the cloud is read.
    const CloudUnits units = a.grow.units();
    if (a.repeat < 1 || a.repeat > kMaxRepeat)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"--repeat must be between 1 and ", std::to_string(kMaxRepeat), ", got ",
                         std::to_string(a.repeat)}));
    const bool both = a.mu.empty() && a.min_pts.empty();
    const std::string mu_text = both ? std::string("1mm:50mm") : a.mu;
    const std::string min_pts_text = both ? std::string("3:40") : a.min_pts;
    const double at_mu_m = parse_length_m(a.grow.mu, "--at-mu");
    if (!(at_mu_m > 0))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"--at-mu must be a positive length, got ", a.grow.mu}));
    if (a.grow.min_pts < 3)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"--at-min-pts must be at least 3 (a plane needs 3 points), got ",
                         std::to_string(a.grow.min_pts)}));
    const GrowerConfig base = a.grow.config(units);  // checks every other growing option

    std::vector<Sweep> sweeps;
    if (!mu_text.empty()) {
        Sweep s{"mu", {}, std::to_string(base.min_pts), {}};
        for (const double mu_m : parse_length_sweep(mu_text, "--mu", a.steps)) {
            GrowOptions o = a.grow;
            o.mu = cat({num(mu_m), "m"});
            s.values.push_back(num(mu_m));
            s.configs.push_back(o.config(units));
        }
        sweeps.push_back(std::move(s));
    }
    if (!min_pts_text.empty()) {
        Sweep s{"min_pts", {}, num(at_mu_m), {}};
        for (const int n :
             parse_count_sweep(min_pts_text, "--min-pts", a.min_pts_steps, 3, kMaxMinPts)) {
            GrowerConfig c = base;
            c.min_pts = n;
            validate(c);
            s.values.push_back(std::to_string(n));
            s.configs.push_back(c);
        }
        sweeps.push_back(std::move(s));
    }
    const fs::path out(a.out);
    std::error_code ec;
    if (fs::exists(out, ec) && !fs::is_directory(out, ec))
        throw Error(ErrorCode::kCannotWrite,
                    cat({"cannot write ", a.out, ": it exists and is not a folder"}));

    const fs::path file = cloud_file(a.input);
    const PointCloud cloud = io::read_cloud(file, io::kPointsOnly);
    std::size_t finite = 0;
    for (const Vec3f& p : cloud.points) finite += p.allFinite() ? 1 : 0;
    if (finite == 0)
        throw Error(ErrorCode::kMalformedInput,
                    cat({file.string(), ": no points to grow (",
                         cloud.empty() ? "the cloud is empty" : "every point is NaN or Inf",
                         "): nothing to sweep"}));
    // Ground truth, found as `surfgrow eval --truth` finds it: labels in the cloud, the faces in
    // scene.json or truth-faces.json beside it.
    std::optional<std::vector<scanner::Face>> faces;
    if (cloud.has_labels()) {
        faces =
            read_truth_faces_in(file.parent_path().empty() ? fs::path(".") : file.parent_path());
        if (faces && units.metres != 1.0)
            throw Error(ErrorCode::kUsage,
                        cat({file.string(), " has ground truth, which is in metres: drop --units ",
                             units.name}));
    }

    const Stopwatch watch;
    std::size_t runs_total = 0, runs_done = 0;
    for (const Sweep& s : sweeps) runs_total += s.configs.size() * std::size_t(a.repeat);
    std::vector<std::pair<std::string, std::string>> csv_files;
    for (const Sweep& s : sweeps)
        csv_files.emplace_back(
            cat({s.name, ".csv"}),
            run_sweep(s, cloud, a.repeat, faces ? &*faces : nullptr, runs_done, runs_total).text());
    const double seconds = watch.seconds();

    const std::string input_name = file.filename().string();
    std::vector<std::string> png_names;
    for (const Sweep& s : sweeps) png_names.push_back(cat({s.name, ".png"}));
    const std::string title = cat({"surfgrow sweep: ", input_name, ", ", std::to_string(finite),
                                   " points", faces ? ", with ground truth" : ""});
    const Plots plots = draw_plots("sweep", csv_files, png_names, title);
    if (!plots.drawn && a.require_plots)
        throw Error(ErrorCode::kCannotWrite,
                    cat({"cannot draw the plots (--require-plots): ", plots.why_not}));

    nlohmann::json record = {
        {"format", "surfgrow-sweep"},
        {"version", 1},
        {"surfgrow_version", SURFGROW_VERSION},
        {"input", input_name},
        {"units", units.name},
        {"points", finite},
        {"ground_truth", faces.has_value()},
        {"seed", base.seed},
        {"repeat", a.repeat},
        {"fixed", {{"mu_m", at_mu_m}, {"min_pts", base.min_pts}}},
    };
    nlohmann::json files = nlohmann::json::array();
    for (const auto& [name, bytes] : csv_files) files.push_back(name);
    for (const auto& [name, bytes] : plots.files) files.push_back(name);
    record["files"] = files;

    publish_study(out, csv_files, plots, "sweep.json", record, "the CSV files are");
    if (!a.quiet) {
        std::string line = cat({"sweep: ", std::to_string(finite), " points"});
        for (const Sweep& s : sweeps) {
            const bool is_mu = s.name == "mu";
            line += cat(
                {", ", std::to_string(s.configs.size()), is_mu ? " mu values " : " min_pts values ",
                 is_mu ? format_length(s.configs.front().mu * units.metres) : s.values.front(),
                 "..", is_mu ? format_length(s.configs.back().mu * units.metres) : s.values.back(),
                 is_mu ? cat({" at min_pts ", std::to_string(base.min_pts)})
                       : cat({" at mu ", format_length(at_mu_m)})});
        }
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.1f s", seconds);
        line += cat({faces ? ", with ground truth" : ", no ground truth", "; ",
                     std::to_string(runs_total), " runs in ", buf, " -> ", a.out,
                     plots.drawn ? " (CSV and plots)" : " (CSV only)"});
        std::cout << line << std::endl;
    }
}

}  // namespace

void add_sweep_command(CLI::App& app) {
    auto* cmd = app.add_subcommand("sweep",
                                   "Grow one cloud over a range of mu and of min-pts: time, "
                                   "surfaces, registered % (and normal "
                                   "error with ground truth) as CSV and plots (paper Fig. 5)");
    auto a = std::make_shared<SweepArgs>();
    cmd->add_option("cloud", a->input,
                    "Input cloud (.ply, .pcd, .xyz, ...), or a scan folder (its cloud.ply)")
        ->required();
    cmd->add_option(
           "-o,--out", a->out,
           "Output folder: mu.csv, min_pts.csv, their plots, sweep.json (written as a whole)")
        ->capture_default_str();
    a->grow.add_to(*cmd);
    // Growing options as `grow` has them, but --mu and --min-pts name ranges here; the values
    // held while the other is swept are --at-mu and --at-min-pts.
    cmd->remove_option(cmd->get_option("--mu"));
    cmd->remove_option(cmd->get_option("--min-pts"));
    cmd->add_option(
        "--mu", a->mu,
        "mu values: FROM:TO (log-spaced, see --steps), a list 4mm,8mm,12mm, or one value "
        "(neither --mu nor --min-pts: 1mm:50mm and 3:40)");
    cmd->add_option("--min-pts", a->min_pts,
                    "min-pts values: FROM:TO (evenly spaced, see --min-pts-steps), a list, or one");
    cmd->add_option("--steps", a->steps, "Number of mu values in a FROM:TO range")
        ->capture_default_str();
    cmd->add_option("--min-pts-steps", a->min_pts_steps,
                    "Number of min-pts values in a FROM:TO range (fewer if they repeat)")
        ->capture_default_str();
    cmd->add_option("--at-mu", a->grow.mu, "mu while min-pts is swept")->capture_default_str();
    cmd->add_option("--at-min-pts", a->grow.min_pts, "min-pts while mu is swept")
        ->capture_default_str();
    cmd->add_option("--repeat", a->repeat,
                    "Runs per value; the CSV's times are those of the run with the median total")
        ->capture_default_str();
    cmd->add_flag("--require-plots", a->require_plots,
                  "Fail (exit 7, nothing written) when the plots cannot be drawn, instead of a "
                  "warning");
    cmd->add_flag("-q,--quiet", a->quiet, "No summary line on stdout");
    cmd->callback([a] { run(*a); });
}

}  // namespace surfgrow::cli
