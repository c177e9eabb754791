#include "surfgrow/io/cloud_io.hpp"

#include <string>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/ascii_scan.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/cloud_layout.hpp"
#include "surfgrow/io/file_bytes.hpp"
#include "surfgrow/io/io_error.hpp"
#include "surfgrow/io/pcd.hpp"
#include "surfgrow/io/ply.hpp"
#include "surfgrow/io/text_cloud.hpp"

namespace surfgrow::io {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    return ext;
}

// Only this much of a file is looked at to tell its format.
constexpr std::size_t kSniffBytes = 4096;

bool looks_like_pcd(std::string_view head) {
    LineReader lines(head);
    std::string_view line;
    std::vector<std::string_view> tok;
    while (lines.next(line)) {
        split_blanks(line, tok, 2);
        if (tok.empty()) continue;
        if (tok[0].starts_with("#")) {
            if (tok[0] == "#" && tok.size() > 1 && tok[1].starts_with(".PCD")) return true;
            continue;
        }
        return tok[0] == "VERSION" || tok[0] == "FIELDS";
    }
    return false;
}

bool looks_like_text(std::string_view head) {
    // Text: printable, and the first rows parse (the last row may be cut by kSniffBytes).
    for (char c : head) {
        if (c == '\0') return false;
    }
    const std::size_t cut = head.size() == kSniffBytes ? head.rfind('\n') : head.size();
    if (cut == std::string_view::npos) return false;
    try {
        (void)read_text_cloud(head.substr(0, cut), "", {});
        return true;
    } catch (const Error&) {
        return false;
    }
}

}  // namespace

std::optional<CloudFormat> format_from_extension(const fs::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".ply") return CloudFormat::kPly;
    if (ext == ".pcd") return CloudFormat::kPcd;
    if (ext == ".xyz" || ext == ".txt" || ext == ".csv" || ext == ".pts") return CloudFormat::kText;
    return std::nullopt;
}

std::optional<CloudFormat> detect_format(std::string_view bytes) {
    const std::string_view head = bytes.substr(0, kSniffBytes);
    if (head.starts_with("ply\n") || head.starts_with("ply\r\n")) return CloudFormat::kPly;
    if (looks_like_pcd(head)) return CloudFormat::kPcd;
    if (looks_like_text(head)) return CloudFormat::kText;
    return std::nullopt;
}

PointCloud read_cloud(std::string_view bytes, CloudFormat format, std::string_view source,
                      const ReadOptions& options) {
    switch (format) {
        case CloudFormat::kPly:
            return read_ply(bytes, source, options);
        case CloudFormat::kPcd:
            return read_pcd(bytes, source, options);
        case CloudFormat::kText:
            break;
    }
    return read_text_cloud(bytes, source, options);
}

PointCloud read_cloud(const fs::path& path, const ReadOptions& options) {
    const FileBytes file = FileBytes::read(path);
    const std::string source = path.string();
    if (file.empty()) throw_malformed(source, "the file is empty");
    std::optional<CloudFormat> format = options.format;
    if (!format) {
        format = format_from_extension(path);
        if (format) {
            // Name the real format when the extension lies about a PLY or PCD file.
            const auto seen = detect_format(file.view());
            if (seen && seen != format && seen != CloudFormat::kText) {
                throw_malformed(source, cat({"the extension says ", to_string(*format),
                                             " but the content is ", to_string(*seen)}));
            }
        } else {
            format = detect_format(file.view());
            if (!format) {
                throw Error(
                    ErrorCode::kUnknownFormat,
                    cat({source, ": unknown format (the extension '", path.extension().string(),
                         "' is not .ply, .pcd, .xyz, .txt, .csv or .pts and the content "
                         "is not recognisable)"}));
            }
        }
    }
    return read_cloud(file.view(), *format, source, options);
}

void write_cloud(const fs::path& path, const CloudView& cloud, const WriteOptions& options) {
    const std::optional<CloudFormat> format =
        options.format ? options.format : format_from_extension(path);
    if (!format) {
        throw Error(
            ErrorCode::kUnknownFormat,
            cat({path.string(), ": cannot tell the format to write from the extension '",
                 path.extension().string(), "' (use .ply, .pcd, .xyz, .txt, .csv or .pts)"}));
    }
    // A cloud the writers would refuse (normals not one per point) leaves no temporary behind.
    (void)layout_for(cloud, options.write_labels, options.write_normals);
    const std::string ext = lower_extension(path);
    const char delimiter = ext == ".csv" ? ',' : ' ';
    const bool count_line = ext == ".pts";  // Leica PTS starts with the point count
    write_atomically(path, [&](std::ostream& out) {
        switch (*format) {
            case CloudFormat::kPly:
                write_ply(out, cloud, options.ply_encoding, options.write_labels,
                          options.write_scans, options.write_normals);
                break;
            case CloudFormat::kPcd:
                write_pcd(out, cloud, options.pcd_encoding, options.write_labels,
                          options.write_normals);
                break;
            case CloudFormat::kText:
                write_text_cloud(out, cloud, delimiter, options.write_labels && options.text_labels,
                                 count_line, options.write_normals);
                break;
        }
    });
}

}  // namespace surfgrow::io
