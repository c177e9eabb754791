// The files `surfgrow grow` writes and later commands read back: surfaces, labels, run record.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/core/grow_result.hpp"
#include "surfgrow/core/grower_config.hpp"

namespace surfgrow::io {

/// What a result needs besides the algorithm's output to be read correctly later.
struct ResultMeta {
    std::string units = "m";       ///< the cloud's length unit, which every length is in
    Vec3d offset = Vec3d::Zero();  ///< PointCloud::offset: added to every position written
    std::string input;             ///< the input file's name, for the record
    /// result_id() of the grown result every file of a folder was derived from (empty in
    /// folders written before it existed). Readers refuse a file whose id is not surfaces.json's.
    std::string result_id;
};

/// A deterministic 16-hex-digit id of a grown result: a hash of its parameters, units, offset,
/// surfaces and labels. Written into every JSON and PLY file of a result folder, so a file left
/// from another run or copied from another folder is recognised; the same input, parameters and
/// seed give the same id, keeping outputs byte-identical.
[[nodiscard]] std::string result_id(const GrowResult& result, const GrowerConfig& config,
                                    const ResultMeta& meta);

/// The labels of a result folder, in binary.
inline constexpr const char* kLabelsFile = "labels.bin";

/// Where surfaces.json (version 2) says its surfaces are, beside it.
inline constexpr const char* kSurfacesFile = "surfaces.ply";

/// surfaces.ply: every surface, one vertex each, binary little-endian, so Open3D, PCL and
/// CloudCompare open it as a point cloud with normals and numpy reads it as one record array:
/// x, y, z (the home point), nx, ny, nz (unit normal), radius, plane_offset (d in n.x + d = 0),
/// point_count, mean_residual, cx, cy, cz (centroid), lambda_min, lambda_mid, lambda_max
/// (eigenvalues), neighbours, tolerance, min_x .. max_z (the members' bounds). All in double, so
/// a command reading the folder back sees exactly what was grown; result_id in a comment.
void write_surfaces_ply(std::ostream& out, std::span<const Surface> surfaces,
                        const ResultMeta& meta);

/// surfaces.json (version 2): parameters and the summary statistics; the surfaces themselves
/// are in surfaces.ply ("surfaces_file"). Deterministic: no timings, no thread count, numbers
/// in shortest round-trip form.
void write_result_json(std::ostream& out, const GrowResult& result, const GrowerConfig& config,
                       const ResultMeta& meta);

/// surfaces.csv: the same surfaces as one row each, for spreadsheets and robot programs.
void write_surfaces_csv(std::ostream& out, std::span<const Surface> surfaces,
                        const ResultMeta& meta);

/// labels.bin: the surface id of every input point (-1 if unregistered), in input order, each a
/// little-endian int32 and nothing else (numpy: np.fromfile("labels.bin", "<i4")).
void write_labels_bin(std::ostream& out, std::span<const std::int32_t> labels);

/// labels.txt: the same as text, one id per line (`--labels-txt`; the only form before labels.bin).
void write_labels_txt(std::ostream& out, std::span<const std::int32_t> labels);

/// A result read back from a folder written by `surfgrow grow`.
struct StoredResult {
    std::vector<Surface> surfaces;  ///< positions relative to meta.offset, as when grown
    GrowStats stats;                ///< without timings; orientation from summary.orientation
    /// The parameters used (lengths in the cloud's units), workspace (viewpoint, crop) included.
    GrowerConfig config;
    ResultMeta meta;
    /// Version 2: the file beside surfaces.json holding the surfaces (filled in by
    /// read_result_json, left empty by parse_result_json). Empty for version 1 (surfaces inline).
    std::string surfaces_file;
};

/// Reads surfaces.json, and for version 2 its surfaces from the surfaces.ply beside it, which
/// must hold as many surfaces as the summary says and carry the same result_id. Throws
/// Error(kCannotOpen) if missing, Error(kMalformedInput) if it is not a surfgrow result.
[[nodiscard]] StoredResult read_result_json(const std::filesystem::path& file);
/// The same for surfaces.json held in memory, without reading any other file; `source` names it
/// in messages.
[[nodiscard]] StoredResult parse_result_json(std::string_view text, std::string_view source);

/// Surfaces read back from surfaces.ply, positions relative to `offset`, and its result_id.
struct StoredSurfaces {
    std::vector<Surface> surfaces;
    std::string result_id;
};
/// Reads surfaces.ply as write_surfaces_ply writes it. Throws Error(kCannotOpen) or
/// Error(kMalformedInput) naming the file and the problem (another layout, truncated, a value
/// that is not finite, a normal that is not a unit vector).
[[nodiscard]] StoredSurfaces read_surfaces_ply(const std::filesystem::path& file,
                                               const Vec3d& offset = Vec3d::Zero());
/// The same for surfaces.ply held in memory; `source` names it in messages.
[[nodiscard]] StoredSurfaces parse_surfaces_ply(std::string_view bytes, std::string_view source,
                                                const Vec3d& offset = Vec3d::Zero());

/// The labels file of result folder `dir`: labels.bin, else labels.txt (folders written before
/// labels.bin, or with --labels-txt alone); labels.bin's path when it has neither.
[[nodiscard]] std::filesystem::path labels_file(const std::filesystem::path& dir);

/// Reads labels.bin or labels.txt, by the file's extension. Throws Error(kCannotOpen /
/// kMalformedInput).
[[nodiscard]] std::vector<std::int32_t> read_labels(const std::filesystem::path& file);

/// The same for labels.bin held in memory; `source` names it in messages. Refuses a size that is
/// not a whole number of labels and an id below -1.
[[nodiscard]] std::vector<std::int32_t> parse_labels_bin(std::string_view bytes,
                                                         std::string_view source);

/// Reads labels.txt. Throws Error(kCannotOpen / kMalformedInput).
[[nodiscard]] std::vector<std::int32_t> read_labels_txt(const std::filesystem::path& file);
/// The same for labels.txt held in memory; `source` names it in messages.
[[nodiscard]] std::vector<std::int32_t> parse_labels_txt(std::string_view text,
                                                         std::string_view source);

/// surfaces.json's "parameters": every parameter of `config`, defaults resolved.
[[nodiscard]] nlohmann::json parameters_json(const GrowerConfig& config);
/// surfaces.json's "summary": the statistics of a run (no timings).
[[nodiscard]] nlohmann::json summary_json(const GrowStats& stats);

/// Name of an OrientationSource as written in surfaces.json.
[[nodiscard]] const char* orientation_name(OrientationSource source);

}  // namespace surfgrow::io
