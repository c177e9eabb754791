// Shared by the end-to-end tests of the CLI: running the real `surfgrow` binary, and a small
// grown result to draw (a box, with bound-plane and coverage-path fixtures).
#pragma once

#include <filesystem>
#include <string>

#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow::test {

struct CliRun {
    int code = -1;
    std::string out;  ///< stdout and stderr together
};

/// Runs `surfgrow <args>` (arguments already shell-quoted where needed); `env` (e.g.
/// "SURFGROW_X=1 ") goes before it.
CliRun run_surfgrow(const std::string& args, const std::string& env = "");

/// A path in single quotes for the shell.
std::string quoted(const std::filesystem::path& p);

/// The outer faces of a box, x in [-0.2, 0.2], y in [-0.15, 0.15], z in [0.4, 0.7] (metres),
/// scanned on a 5 mm grid with 1 mm noise, a few NaN points mixed in; grown by `surfgrow grow`
/// with --seed 1. Normals face the frame origin, below the box: from outside, the near faces are
/// seen from behind and the far ones from the front.
struct GrownBox {
    std::filesystem::path cloud;  ///< box.ply
    std::filesystem::path out;    ///< the result folder
    PointCloud points;            ///< the cloud as written
    io::StoredResult result;      ///< out/surfaces.json read back
};
/// `grow_args` are added to the command (e.g. " --viewpoint 0,0,0m": the same normals, with the
/// sensor on record).
GrownBox grow_box(const std::filesystem::path& dir, const std::string& grow_args = "");

/// Writes out/planes.json (one bound plane per box face: its rectangle and the surfaces on it)
/// and out/coverage.json (a zigzag of goals just inside the face x = -0.2), as `surfgrow planes`
/// and `surfgrow coverage` write them. Returns the number of goals.
std::size_t write_layer_fixtures(const GrownBox& box);

}  // namespace surfgrow::test
