// Evaluating a result folder against a scan folder's ground truth: shared by `eval` and `demo`.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/eval/evaluation.hpp"
#include "surfgrow/eval/requirement.hpp"
#include "surfgrow/scanner/primitives.hpp"

namespace surfgrow::cli {

/// The evaluation's options as given on the command line.
struct EvalSettings {
    std::string workspace = "1m";      ///< workspace radius around each point's scan origin
    std::string band = "0.5m";         ///< width of the range bands
    std::vector<std::string> require;  ///< bounds, e.g. "registered>=0.99,normal_median<=3"

    void add_to(CLI::App& cmd);
    /// Throws Error(kUsage) for a length without unit or a bad bound.
    [[nodiscard]] eval::EvalOptions options() const;
    [[nodiscard]] std::vector<eval::Requirement> requirements() const;
};

/// What a scan folder (`surfgrow scan -o DIR`) holds for evaluation.
struct Truth {
    std::filesystem::path cloud_file;
    PointCloud cloud;  ///< metres, truth face per point, scan per point
    std::vector<scanner::Face> faces;
};

/// The faces of a scan folder: DIR/scene.json, else DIR/truth-faces.json; nullopt when DIR has
/// neither. Throws the readers' errors for a file that is there but broken.
[[nodiscard]] std::optional<std::vector<scanner::Face>> read_truth_faces_in(
    const std::filesystem::path& dir);

/// Reads DIR/cloud.ply and the faces from DIR/scene.json (or DIR/truth-faces.json when there is
/// no scene file). Throws Error(kCannotOpen) when they are missing, and the readers' errors.
[[nodiscard]] Truth read_truth(const std::filesystem::path& dir);

/// Evaluates the result in `result_dir` (surfaces.json, labels.bin) against `truth`, converting
/// the result to metres. Throws Error(kInvalidParameter) when the result is not one of this
/// cloud (a different point count).
[[nodiscard]] eval::EvalReport evaluate_folder(const std::filesystem::path& result_dir,
                                               const Truth& truth,
                                               const eval::EvalOptions& options);

/// Writes `file` (RESULT/eval.json) into its result folder by an output transaction.
void write_eval_json(const std::filesystem::path& file, const eval::EvalReport& report,
                     const std::vector<eval::RequirementCheck>& checks);

/// Throws OutcomeError(kRequirementFailed) naming every bound that does not hold.
void enforce(const std::vector<eval::RequirementCheck>& checks);

}  // namespace surfgrow::cli
