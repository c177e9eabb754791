// Shared by `sweep` and `study`: parameter ranges from the command line, CSV tables, timing
// medians, and the plots drawn from the tables by scripts/plots/surfgrow_plots.py.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "surfgrow/core/grow_result.hpp"

namespace surfgrow::cli {

/// Most values one range may expand to (--steps and lists).
inline constexpr int kMaxSweepValues = 200;
/// Most repetitions of one run for the timing median (--repeat).
inline constexpr int kMaxRepeat = 50;

/// Lengths to sweep, in metres, increasing: "1mm:50mm" gives `steps` values spaced evenly on a
/// log scale from 1 mm to 50 mm, each rounded to 3 significant digits (the ends are kept as
/// given); "4mm,8mm,12mm" a list; "12mm" one value. Every length needs its unit.
/// Throws Error(kUsage) for bad syntax or a missing unit and Error(kInvalidParameter) for a
/// length <= 0, a range that does not increase, or more than kMaxSweepValues values.
[[nodiscard]] std::vector<double> parse_length_sweep(std::string_view text, std::string_view option,
                                                     int steps);

/// Whole numbers to sweep, increasing: "3:40" gives about `steps` values evenly spaced from 3 to
/// 40 (rounded, duplicates dropped); "5,10,20" a list; "10" one value. Each must lie in
/// [lo, hi]. Errors as parse_length_sweep.
[[nodiscard]] std::vector<int> parse_count_sweep(std::string_view text, std::string_view option,
                                                 int steps, int lo, int hi);

/// Point counts, increasing: "10k:1M" gives `steps` values spaced evenly on a log scale, rounded
/// to 2 significant digits; "20000,50k,1e5" a list. Suffixes k (10^3) and M (10^6). Each must
/// lie in [lo, hi]. Errors as parse_length_sweep.
[[nodiscard]] std::vector<std::uint64_t> parse_size_sweep(std::string_view text,
                                                          std::string_view option, int steps,
                                                          std::uint64_t lo, std::uint64_t hi);

/// Throws Error(kInvalidParameter) unless 1 <= value <= hi, naming `option`.
void check_count(int value, std::string_view option, int hi);

/// A CSV table: a header line and rows of already formatted fields.
struct CsvTable {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    [[nodiscard]] std::string text() const;
};

/// Fixed-point text of a number with `decimals` digits; "" for NaN (an empty CSV field).
[[nodiscard]] std::string fixed(double value, int decimals);

/// The columns every row of a sweep or study shares, after its parameters: the deterministic
/// figures, then (always last, so a diff can drop them) the timings.
[[nodiscard]] std::vector<std::string> result_columns(bool truth);
[[nodiscard]] std::vector<std::string> timing_columns();
/// Fields for result_columns(): points, surfaces, registered %, by growing alone, reduction, and
/// (when `normal_deg` is given) the normal error's median and p95.
[[nodiscard]] std::vector<std::string> result_fields(const GrowStats& stats,
                                                     const std::pair<double, double>* normal_deg);
/// Fields for timing_columns(): algorithm seconds, then index, grow, attach, finish.
[[nodiscard]] std::vector<std::string> timing_fields(const StageTimes& t);

/// The times of the run with the median total among repeated runs (of an even count, the
/// faster of the middle two): its stages add up to its total, so a stacked plot stays true.
[[nodiscard]] StageTimes median_run(const std::vector<StageTimes>& runs);

/// Pictures drawn from CSV files by the plot script, as bytes to stage into an output.
struct Plots {
    bool drawn = false;
    std::string why_not;  ///< when not drawn: why, for the warning
    std::vector<std::pair<std::string, std::string>> files;  ///< name, PNG bytes
};

/// Writes `csv_files` (name, bytes) into a fresh temporary folder, runs
/// `python surfgrow_plots.py <kind> <folder> --title <title>` and reads back `png_names`. Never
/// throws for a missing Python, matplotlib or script: the reason is returned instead.
///
/// The script is found in $SURFGROW_PLOT_SCRIPT_DIR when set (and only there), else in
/// <binary>/../share/surfgrow/plots, else in the source tree's scripts/plots. The interpreter is
/// /usr/bin/python3 (Debian's, which has python3-matplotlib) unless $SURFGROW_PYTHON names another.
[[nodiscard]] Plots draw_plots(std::string_view kind,
                               const std::vector<std::pair<std::string, std::string>>& csv_files,
                               const std::vector<std::string>& png_names, const std::string& title);

/// Publishes a study's outputs as one transaction into `out`: the CSV files, the plots and
/// `record_name` (the run record as JSON). When the plots were not drawn, warns on stderr that
/// `written` (e.g. "study.csv is") was written without them.
void publish_study(const std::filesystem::path& out,
                   const std::vector<std::pair<std::string, std::string>>& csv_files,
                   const Plots& plots, const std::string& record_name, const nlohmann::json& record,
                   std::string_view written);

}  // namespace surfgrow::cli
