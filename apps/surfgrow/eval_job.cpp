#include "eval_job.hpp"

#include "exit_status.hpp"

#include <cmath>

#include "cli_common.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/eval/plane_evaluation.hpp"
#include "surfgrow/eval/report_json.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/io/result_folder.hpp"
#include "surfgrow/io/results_io.hpp"
#include "surfgrow/io/scene_file.hpp"
#include "surfgrow/io/truth_faces_file.hpp"
#include "surfgrow/scanner/scene.hpp"

namespace surfgrow::cli {

namespace fs = std::filesystem;

void EvalSettings::add_to(CLI::App& cmd) {
    cmd.add_option("--workspace", workspace,
                   "Workspace radius around each point's scan origin, for the 'within' figures")
        ->capture_default_str();
    cmd.add_option("--band", band, "Width of the range bands")->capture_default_str();
    cmd.add_option("--require", require,
                   "Bounds that must hold, e.g. registered>=0.99,normal_median<=3 (exit code 9 "
                   "otherwise)");
}

eval::EvalOptions EvalSettings::options() const {
    eval::EvalOptions o;
    o.workspace_m = parse_length_m(workspace, "--workspace");
    o.band_m = parse_length_m(band, "--band");
    if (!(o.workspace_m > 0))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"--workspace must be positive, got ", workspace}));
    if (!(o.band_m >= 0.01))
        throw Error(ErrorCode::kInvalidParameter, cat({"--band must be at least 1cm, got ", band}));
    return o;
}

std::vector<eval::Requirement> EvalSettings::requirements() const {
    std::vector<eval::Requirement> all;
    for (const std::string& r : require) {
        for (eval::Requirement& one : eval::parse_requirements(r)) all.push_back(std::move(one));
    }
    return all;
}

Truth read_truth(const fs::path& dir) {
    if (!fs::is_directory(dir))
        throw Error(ErrorCode::kCannotOpen,
                    cat({dir.string(), ": not a folder (expected the output of surfgrow scan)"}));
    Truth t;
    t.cloud_file = dir / "cloud.ply";
    if (!fs::exists(t.cloud_file))
        throw Error(
            ErrorCode::kCannotOpen,
            cat({t.cloud_file.string(), ": missing (expected the output of surfgrow scan)"}));
    t.cloud = io::read_cloud(t.cloud_file, io::kPointsOnly);
    if (!t.cloud.has_labels() && !t.cloud.empty())
        throw Error(ErrorCode::kMalformedInput,
                    cat({t.cloud_file.string(), ": no ground-truth label per point"}));
    std::optional<std::vector<scanner::Face>> faces = read_truth_faces_in(dir);
    if (!faces)
        throw Error(ErrorCode::kCannotOpen,
                    cat({dir.string(), ": neither scene.json nor truth-faces.json"}));
    t.faces = std::move(*faces);
    return t;
}

std::optional<std::vector<scanner::Face>> read_truth_faces_in(const fs::path& dir) {
    if (fs::exists(dir / "scene.json"))
        return scanner::Scene(io::read_scene_file(dir / "scene.json")).faces();
    if (fs::exists(dir / "truth-faces.json")) return io::read_truth_faces(dir / "truth-faces.json");
    return std::nullopt;
}

eval::EvalReport evaluate_folder(const fs::path& result_dir, const Truth& truth,
                                 const eval::EvalOptions& options) {
    io::StoredResult result = io::read_result_folder(result_dir).result;
    const std::filesystem::path labels_path = io::labels_file(result_dir);
    const std::vector<std::int32_t> labels = io::read_labels(labels_path);
    if (labels.size() != truth.cloud.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({labels_path.string(), ": ", std::to_string(labels.size()), " labels, but ",
                         truth.cloud_file.string(), " has ", std::to_string(truth.cloud.size()),
                         " points: not a result of this scan"}));
    // The result in metres, relative to the truth cloud's offset.
    const double scale = unit_to_metres(result.meta.units, "surfaces.json units");
    const Vec3d shift = result.meta.offset * scale - truth.cloud.offset;
    for (Surface& s : result.surfaces) {
        s.home = s.home * scale + shift;
        s.centroid = s.centroid * scale + shift;
        s.radius *= scale;
        s.mean_residual *= scale;
        s.eigenvalues *= scale * scale;
    }
    const eval::GrowOutcome grown{result.surfaces, labels, &result.stats};
    eval::EvalReport report = eval::evaluate(truth.cloud, grown, truth.faces, options);
    // The bound planes too, where the result has them: normals are unit-free, and the planes
    // name their member surfaces by id.
    const fs::path planes_file = result_dir / "planes.json";
    if (fs::exists(planes_file)) {
        const io::StoredPlanes planes = io::read_planes_json(planes_file);
        io::check_derived_file(planes_file, planes.meta, planes.planes.plane_of_patch.size(),
                               result, "run `surfgrow planes` again");
        eval::add_plane_figures(report, truth.cloud, grown, planes.planes, truth.faces);
    }
    return report;
}

void write_eval_json(const fs::path& file, const eval::EvalReport& report,
                     const std::vector<eval::RequirementCheck>& checks) {
    const std::string text = eval::to_json(report, checks).dump(2) + "\n";
    // Into the result folder through its transaction: its lock, and no mix with a run replacing it.
    io::OutputTransaction tx(file.parent_path());
    tx.add(file.filename().string(), [&](std::ostream& o) { o << text; });
    tx.commit();
}

void enforce(const std::vector<eval::RequirementCheck>& checks) {
    std::string failed;
    std::size_t count = 0;
    for (const eval::RequirementCheck& c : checks) {
        if (c.met) continue;
        ++count;
        failed += cat({failed.empty() ? "" : ", ", c.requirement.text, " (got ",
                       std::isfinite(c.value) ? num(c.value) : std::string("n/a"), ")"});
    }
    if (count)
        throw OutcomeError(Outcome::kRequirementFailed,
                           cat({std::to_string(count), " of ", std::to_string(checks.size()),
                                " requirements failed: ", failed}));
}

}  // namespace surfgrow::cli
