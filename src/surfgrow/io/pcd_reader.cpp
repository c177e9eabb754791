// Reading PCD: the header's field table, then an ascii, binary or LZF-compressed body.
#include <liblzf/lzf.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "surfgrow/io/ascii_scan.hpp"
#include "surfgrow/io/binary_columns.hpp"
#include "surfgrow/io/io_error.hpp"
#include "surfgrow/io/pcd.hpp"
#include "surfgrow/io/point_builder.hpp"
#include "surfgrow/io/scalar_type.hpp"

namespace surfgrow::io {

namespace {

// A header longer than this is not a PCD header (it is a few hundred bytes in practice).
constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;
constexpr std::size_t kMaxHeaderLine = std::size_t{1} << 16;

// LZF encodes at most 264 bytes in a 3-byte back reference, so no valid block expands more than
// 88-fold: a larger claimed size is a lie, refused before allocating for it.
constexpr uint64_t kMaxLzfRatio = 90;

constexpr std::array<std::string_view, 3> kAxisNames{"x", "y", "z"};
// PCL's names (pcl::Normal, pcl::PointNormal).
constexpr std::array<std::string_view, 3> kNormalNames{"normal_x", "normal_y", "normal_z"};

struct Field {
    std::string_view name;  // views into the file's bytes
    ScalarType type = ScalarType::kFloat32;
    uint64_t count = 1;
    [[nodiscard]] uint64_t bytes() const { return scalar_size(type) * count; }
    [[nodiscard]] bool is_padding() const { return name == "_"; }
};

struct Header {
    std::vector<Field> fields;
    uint64_t points = 0;
    std::array<double, 7> viewpoint{0, 0, 0, 1, 0, 0, 0};
    PcdEncoding data = PcdEncoding::kAscii;
    std::size_t body_offset = 0;
    std::size_t body_first_line = 0;
};

// The header's lines by keyword, before they are checked against each other.
struct RawHeader {
    std::vector<std::string_view> fields, sizes, types, counts;
    std::optional<uint64_t> width, height, points;
    bool have_viewpoint = false;
};

bool is_keyword(std::string_view kw) {
    static constexpr std::array<std::string_view, 11> kKeywords{
        "VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE",     "COUNT",
        "WIDTH",   "HEIGHT", "POINTS",  "DATA", "VIEWPOINT"};
    for (std::string_view k : kKeywords) {
        if (k == kw) return true;
    }
    return false;
}

void take_list(std::vector<std::string_view>& dst, const std::vector<std::string_view>& tok,
               std::string_view src, std::size_t line) {
    if (!dst.empty()) throw_malformed_line(src, line, cat({"a second ", tok[0], " line"}));
    if (tok.size() < 2) throw_malformed_line(src, line, cat({tok[0], " lists no values"}));
    dst.assign(tok.begin() + 1, tok.end());
}

uint64_t take_count(const std::vector<std::string_view>& tok, std::string_view src,
                    std::size_t line) {
    uint64_t v = 0;
    if (tok.size() != 2 || !parse_uint(tok[1], v)) {
        throw_malformed_line(src, line, cat({tok[0], " must be one whole number >= 0"}));
    }
    return v;
}

PcdEncoding data_kind(std::string_view kind, std::string_view src, std::size_t line) {
    std::string lower(kind);
    for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    if (lower == "ascii") return PcdEncoding::kAscii;
    if (lower == "binary") return PcdEncoding::kBinary;
    if (lower == "binary_compressed") return PcdEncoding::kBinaryCompressed;
    throw_malformed_line(src, line, cat({"unknown DATA kind ", quoted(kind)}));
}

// Checks the field table (FIELDS, SIZE, TYPE, COUNT agree) and the point counts.
void build_fields(const RawHeader& raw, Header& h, std::string_view src) {
    const std::size_t n = raw.fields.size();
    if (n == 0) throw_malformed(src, "the header has no FIELDS line");
    if (raw.sizes.size() != n || raw.types.size() != n ||
        (!raw.counts.empty() && raw.counts.size() != n)) {
        throw_malformed(src,
                        cat({"FIELDS names ", count_str(n), " fields but SIZE has ",
                             count_str(raw.sizes.size()), ", TYPE ", count_str(raw.types.size()),
                             " and COUNT ", count_str(raw.counts.size()), " values"}));
    }
    for (std::size_t i = 0; i < n; ++i) {
        Field f;
        f.name = raw.fields[i];
        uint64_t size = 0;
        if (!parse_uint(raw.sizes[i], size)) {
            throw_malformed(src, cat({"field ", f.name, " has SIZE ", quoted(raw.sizes[i]),
                                      ", not a whole number"}));
        }
        const auto type =
            raw.types[i].size() == 1 ? pcd_scalar_type(raw.types[i][0], size) : std::nullopt;
        if (!type) {
            throw_malformed(src,
                            cat({"field ", f.name, " has TYPE ", quoted(raw.types[i]), " and SIZE ",
                                 quoted(raw.sizes[i]), ", a combination PCD does not define"}));
        }
        f.type = *type;
        if (!raw.counts.empty() && (!parse_uint(raw.counts[i], f.count) || f.count == 0)) {
            throw_malformed(src, cat({"field ", f.name, " has COUNT ", quoted(raw.counts[i]),
                                      "; it must be a whole number >= 1"}));
        }
        h.fields.push_back(f);
    }

    const uint64_t height = raw.height.value_or(1);
    if (raw.width) {
        uint64_t wh = 0;
        if (!checked_mul(*raw.width, height, wh)) {
            throw_malformed(src, cat({"WIDTH ", count_str(*raw.width), " x HEIGHT ",
                                      count_str(height), " exceeds 2^64 points"}));
        }
        if (raw.points && *raw.points != wh) {
            throw_malformed(src,
                            cat({"WIDTH ", count_str(*raw.width), " x HEIGHT ", count_str(height),
                                 " does not equal POINTS ", count_str(*raw.points)}));
        }
        h.points = wh;
    } else if (raw.points) {
        h.points = *raw.points;
    } else {
        throw_malformed(src, "the header has neither WIDTH nor POINTS");
    }
}

Header parse_header(std::string_view bytes, std::string_view src) {
    LineReader lines(bytes);
    std::string_view line;
    std::vector<std::string_view> tok;
    RawHeader raw;
    Header h;
    bool first = true;
    while (true) {
        if (lines.offset() > kMaxHeaderBytes) {
            throw_malformed(src, "no DATA line in the first MiB; not a PCD header");
        }
        if (!lines.next(line)) {
            throw_malformed(src, first ? "not a PCD file (no header)"
                                       : "the header ends before its DATA line (truncated file?)");
        }
        const std::size_t n = lines.line_number();
        if (line.size() > kMaxHeaderLine) {
            throw_malformed(src, first ? "not a PCD file (it does not start with a PCD header)"
                                       : cat({"header line ", count_str(n), " is too long"}));
        }
        split_blanks(line, tok);
        if (tok.empty() || tok[0][0] == '#') continue;
        const std::string_view kw = tok[0];
        if (!is_keyword(kw)) {
            if (first) throw_malformed(src, "not a PCD file (it does not start with a PCD header)");
            throw_malformed_line(src, n, cat({"unknown header keyword ", quoted(kw)}));
        }
        first = false;
        if (kw == "VERSION") {
            continue;  // 0.7, .7, 0.6...: the layout rules below are the same
        } else if (kw == "FIELDS" || kw == "COLUMNS") {
            take_list(raw.fields, tok, src, n);
        } else if (kw == "SIZE") {
            take_list(raw.sizes, tok, src, n);
        } else if (kw == "TYPE") {
            take_list(raw.types, tok, src, n);
        } else if (kw == "COUNT") {
            take_list(raw.counts, tok, src, n);
        } else if (kw == "WIDTH") {
            raw.width = take_count(tok, src, n);
        } else if (kw == "HEIGHT") {
            raw.height = take_count(tok, src, n);
        } else if (kw == "POINTS") {
            raw.points = take_count(tok, src, n);
        } else if (kw == "VIEWPOINT") {
            if (tok.size() != 8) throw_malformed_line(src, n, "VIEWPOINT needs 7 numbers");
            for (std::size_t i = 0; i < 7; ++i) {
                if (!parse_double(tok[i + 1], h.viewpoint[i])) {
                    throw_malformed_line(
                        src, n, cat({"VIEWPOINT value ", quoted(tok[i + 1]), " is not a number"}));
                }
            }
        } else {  // DATA ends the header
            if (tok.size() != 2) throw_malformed_line(src, n, "expected 'DATA <kind>'");
            h.data = data_kind(tok[1], src, n);
            break;
        }
    }
    build_fields(raw, h, src);
    h.body_offset = lines.offset();
    h.body_first_line = lines.line_number() + 1;
    return h;
}

// Which field feeds what: indices into Header::fields.
struct FieldLayout {
    std::array<std::size_t, 3> xyz{};
    std::optional<std::size_t> label;
    std::optional<std::array<std::size_t, 3>> normals;  // all three or none
    bool wide = false;  // a coordinate type wider than float: the offset rule applies
};

FieldLayout field_layout(const Header& h, std::string_view src, const ReadOptions& options) {
    FieldLayout layout;
    std::array<bool, 3> found{false, false, false};
    // The first field of each normal name decides; one with COUNT above 1 means no normals.
    std::array<std::optional<std::size_t>, 3> normal;
    bool normals_usable = options.read_normals;
    for (std::size_t i = 0; i < h.fields.size(); ++i) {
        const Field& f = h.fields[i];
        for (std::size_t a = 0; a < 3; ++a) {
            if (f.name != kNormalNames[a] || normal[a]) continue;
            normal[a] = i;
            normals_usable = normals_usable && f.count == 1;
        }
        for (std::size_t a = 0; a < 3; ++a) {
            if (f.name != kAxisNames[a]) continue;
            if (found[a]) throw_malformed(src, cat({"field ", f.name, " appears twice"}));
            if (f.count != 1) {
                throw_malformed(src, cat({"field ", f.name, " has COUNT ", count_str(f.count),
                                          "; a coordinate needs 1"}));
            }
            found[a] = true;
            layout.xyz[a] = i;
            layout.wide = layout.wide || is_wide(f.type);
        }
        if (options.read_labels && f.name == options.label_field && !layout.label) {
            if (f.count != 1) {
                throw_malformed(src, cat({"field ", f.name, " has COUNT ", count_str(f.count),
                                          "; a label needs 1"}));
            }
            layout.label = i;
        }
    }
    for (std::size_t a = 0; a < 3; ++a) {
        if (!found[a]) throw_malformed(src, cat({"the header has no field ", kAxisNames[a]}));
    }
    if (normals_usable && normal[0] && normal[1] && normal[2]) {
        layout.normals = std::array<std::size_t, 3>{*normal[0], *normal[1], *normal[2]};
    }
    return layout;
}

void check_fits(uint64_t points, uint64_t record, std::size_t left, std::string_view src) {
    uint64_t need = 0;
    if (!checked_mul(points, record, need) || need > left) {
        throw_malformed(src,
                        cat({"header says ", count_str(points), " points of ", count_str(record),
                             " bytes but only ", count_str(left), " bytes follow"}));
    }
}

void read_ascii(std::string_view bytes, const Header& h, const FieldLayout& layout,
                std::string_view src, PointCloud& cloud) {
    // Token index of each field's first value on a line.
    std::vector<std::size_t> first_value;
    uint64_t values = 0;
    for (const Field& f : h.fields) {
        first_value.push_back(static_cast<std::size_t>(values));
        if (!checked_add(values, f.count, values)) {
            throw_malformed(src, "the fields' COUNTs add up beyond 2^64");
        }
    }
    const std::string_view body = bytes.substr(h.body_offset);
    // Every value takes at least two bytes (a digit and a separator): reserve no more points
    // than the text can hold, whatever the header claims.
    const uint64_t fit = body.size() / values / 2 + 1;
    cloud.points.reserve(std::min(h.points, fit));
    if (layout.label) cloud.labels.reserve(std::min(h.points, fit));
    if (layout.normals) cloud.normals.reserve(std::min(h.points, fit));
    PointBuilder builder(cloud, layout.wide);
    LineReader lines(body, h.body_first_line);
    std::vector<std::string_view> tok;
    std::string_view line;
    uint64_t read = 0;
    while (read < h.points) {
        if (!lines.next(line)) {
            throw_malformed(src, cat({"header says ", count_str(h.points),
                                      " points but the data ends after ", count_str(read)}));
        }
        split_blanks(line, tok, values + 1);
        if (tok.empty()) continue;
        const std::size_t n = lines.line_number();
        if (tok.size() != values) {
            throw_malformed_line(src, n,
                                 cat({"expected ", count_str(values), " values, found ",
                                      tok.size() > values ? "more" : count_str(tok.size())}));
        }
        double xyz[3];
        for (std::size_t a = 0; a < 3; ++a) {
            const std::string_view t = tok[first_value[layout.xyz[a]]];
            if (!parse_double(t, xyz[a])) {
                throw_malformed_line(src, n, cat({quoted(t), " is not a number"}));
            }
        }
        if (layout.normals) {
            Vec3f normal = Vec3f::Zero();
            for (std::size_t a = 0; a < 3; ++a) {
                const std::string_view t = tok[first_value[(*layout.normals)[a]]];
                // Straight to float: the writer's shortest text comes back exactly.
                if (!parse_float(t, normal[static_cast<int>(a)])) {
                    throw_malformed_line(
                        src, n, cat({kNormalNames[a], " ", quoted(t), " is not a number"}));
                }
            }
            cloud.normals.push_back(normal);
        }
        if (layout.label) {
            const std::string_view t = tok[first_value[*layout.label]];
            double v = 0;
            int32_t label = 0;
            if (!parse_double(t, v) || !label_from_double(v, label)) {
                throw_malformed_line(src, n,
                                     cat({"label ", quoted(t), " is not a 32-bit integer"}));
            }
            cloud.labels.push_back(label);
        }
        builder.add(xyz[0], xyz[1], xyz[2]);
        ++read;
    }
    while (lines.next(line)) {
        if (!trim(line).empty()) {
            throw_malformed_line(
                src, lines.line_number(),
                cat({"more points than the ", count_str(h.points), " the header declares"}));
        }
    }
}

void read_binary(std::string_view bytes, const Header& h, const FieldLayout& layout, bool swap,
                 std::string_view src, PointCloud& cloud) {
    // Records are the fields in order, padding included; the fields' offsets follow.
    std::vector<std::size_t> offset;
    uint64_t record = 0;
    for (const Field& f : h.fields) {
        offset.push_back(static_cast<std::size_t>(record));
        if (!checked_add(record, f.bytes(), record) || f.bytes() / scalar_size(f.type) != f.count) {
            throw_malformed(src, "the fields' sizes add up beyond 2^64 bytes");
        }
    }
    const std::size_t left = bytes.size() - h.body_offset;
    check_fits(h.points, record, left, src);
    const auto column = [&](std::size_t i) {
        return Column{h.body_offset + offset[i], static_cast<std::size_t>(record),
                      h.fields[i].type};
    };
    const std::array<Column, 3> xyz{column(layout.xyz[0]), column(layout.xyz[1]),
                                    column(layout.xyz[2])};
    Column label;
    if (layout.label) label = column(*layout.label);
    std::array<Column, 3> normals;
    for (std::size_t a = 0; a < 3 && layout.normals; ++a) normals[a] = column((*layout.normals)[a]);
    read_columns(bytes.data(), h.points, xyz, layout.label ? &label : nullptr,
                 layout.normals ? &normals : nullptr, swap, src, cloud);
    check_padding_tail(bytes, h.body_offset + h.points * record, src);
}

uint32_t load_u32_le(const char* p) {
    return kHostIsLittleEndian ? load_value<uint32_t, false>(p) : load_value<uint32_t, true>(p);
}

void read_compressed(std::string_view bytes, const Header& h, const FieldLayout& layout, bool swap,
                     std::string_view src, PointCloud& cloud) {
    // PCL stores each non-padding field's values contiguously (x x x ... y y y ...), then
    // compresses the whole with LZF.
    std::vector<uint64_t> offset(h.fields.size(), 0);
    uint64_t record = 0;
    for (std::size_t i = 0; i < h.fields.size(); ++i) {
        offset[i] = record;
        if (h.fields[i].is_padding()) continue;
        const uint64_t b = h.fields[i].bytes();
        if (!checked_add(record, b, record) ||
            b / scalar_size(h.fields[i].type) != h.fields[i].count) {
            throw_malformed(src, "the fields' sizes add up beyond 2^64 bytes");
        }
    }
    const std::size_t left = bytes.size() - h.body_offset;
    if (left < 8) {
        throw_malformed(src,
                        "the binary_compressed data lacks its two size words (truncated file?)");
    }
    const char* in = bytes.data() + h.body_offset;
    const uint32_t compressed = load_u32_le(in);
    const uint32_t uncompressed = load_u32_le(in + 4);
    if (compressed > left - 8) {
        throw_malformed(src, cat({"the compressed block says ", count_str(compressed),
                                  " bytes but only ", count_str(left - 8), " bytes follow"}));
    }
    uint64_t expected = 0;
    if (!checked_mul(h.points, record, expected) || expected != uncompressed) {
        throw_malformed(src, cat({"the compressed block says ", count_str(uncompressed),
                                  " bytes uncompressed but header says ", count_str(h.points),
                                  " points of ", count_str(record), " bytes"}));
    }
    if (uncompressed > uint64_t{compressed} * kMaxLzfRatio + 64) {
        throw_malformed(src,
                        cat({"a compressed block of ", count_str(compressed), " bytes cannot hold ",
                             count_str(uncompressed), " bytes of LZF data"}));
    }
    auto buf = std::make_unique_for_overwrite<char[]>(uncompressed == 0 ? 1 : uncompressed);
    if (uncompressed > 0) {
        const unsigned got = lzf_decompress(in + 8, compressed, buf.get(), uncompressed);
        if (got != uncompressed) {
            throw_malformed(src, "the binary_compressed data does not decompress (corrupt LZF)");
        }
    }
    const auto column = [&](std::size_t i) {
        const Field& f = h.fields[i];
        return Column{static_cast<std::size_t>(offset[i] * h.points),
                      static_cast<std::size_t>(f.bytes()), f.type};
    };
    const std::array<Column, 3> xyz{column(layout.xyz[0]), column(layout.xyz[1]),
                                    column(layout.xyz[2])};
    Column label;
    if (layout.label) label = column(*layout.label);
    std::array<Column, 3> normals;
    for (std::size_t a = 0; a < 3 && layout.normals; ++a) normals[a] = column((*layout.normals)[a]);
    read_columns(buf.get(), h.points, xyz, layout.label ? &label : nullptr,
                 layout.normals ? &normals : nullptr, swap, src, cloud);
    check_padding_tail(bytes, h.body_offset + 8 + compressed, src);
}

}  // namespace

PointCloud read_pcd(std::string_view bytes, std::string_view source, const ReadOptions& options) {
    if (bytes.empty()) throw_malformed(source, "the file is empty");
    const Header h = parse_header(bytes, source);
    const FieldLayout layout = field_layout(h, source, options);
    // PCL writes binary data in the writer's byte order, which is little-endian in practice.
    const bool swap = !kHostIsLittleEndian;

    PointCloud cloud;
    switch (h.data) {
        case PcdEncoding::kAscii:
            read_ascii(bytes, h, layout, source, cloud);
            break;
        case PcdEncoding::kBinary:
            read_binary(bytes, h, layout, swap, source, cloud);
            break;
        case PcdEncoding::kBinaryCompressed:
            read_compressed(bytes, h, layout, swap, source, cloud);
            break;
    }
    // The default viewpoint says nothing about where the sensor was.
    constexpr std::array<double, 7> kDefault{0, 0, 0, 1, 0, 0, 0};
    if (h.viewpoint != kDefault) {
        cloud.viewpoint = Vec3d(h.viewpoint[0], h.viewpoint[1], h.viewpoint[2]) - cloud.offset;
    }
    return cloud;
}

}  // namespace surfgrow::io
