// Reading and writing point-cloud files of any supported format (PLY, PCD, text).
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/io/cloud_options.hpp"

namespace surfgrow::io {

/// The format an extension stands for (case-insensitive): .ply, .pcd, and .xyz .txt .csv .pts
/// for text; nullopt for any other.
[[nodiscard]] std::optional<CloudFormat> format_from_extension(const std::filesystem::path& path);

/// The format a file's first bytes show: "ply" for PLY, a PCD header (comments, then VERSION or
/// FIELDS), or text rows of numbers (optionally under a header row naming x, y, z); nullopt
/// when none fits.
[[nodiscard]] std::optional<CloudFormat> detect_format(std::string_view bytes);

/// Reads a cloud held in memory as `format`; `source` names it in messages.
[[nodiscard]] PointCloud read_cloud(std::string_view bytes, CloudFormat format,
                                    std::string_view source, const ReadOptions& options = {});

/// Reads a point-cloud file. The format comes from options.format, else the extension (and the
/// content must then be of that format), else the content.
///
/// Points keep the file's order, NaN ones included. Throws Error with kCannotOpen (missing,
/// a folder, unreadable), kUnknownFormat (no known extension and unrecognisable content) or
/// kMalformedInput (empty, broken, truncated, counts that do not match the size); every message
/// names the file.
[[nodiscard]] PointCloud read_cloud(const std::filesystem::path& path,
                                    const ReadOptions& options = {});

/// Writes `cloud` to `path` atomically (a temporary file renamed into place), in options.format
/// or else the extension's format (.csv: comma-separated; .pts: a first line with the point
/// count). Normals (PointCloud::normals) and labels are written as options says (WriteOptions).
/// Throws Error(kUnknownFormat) for an unknown extension without options.format,
/// Error(kInvalidParameter) for normals that are not one per point (nothing is written, `path`
/// keeps its old content), Error(kCannotWrite) when the file cannot be written.
void write_cloud(const std::filesystem::path& path, const CloudView& cloud,
                 const WriteOptions& options = {});

}  // namespace surfgrow::io
