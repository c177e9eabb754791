#include "surfgrow/io/text_cloud.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "surfgrow/io/ascii_scan.hpp"
#include "surfgrow/io/cloud_layout.hpp"
#include "surfgrow/io/io_error.hpp"
#include "surfgrow/io/output_buffer.hpp"
#include "surfgrow/io/point_builder.hpp"

namespace surfgrow::io {

namespace {

// More columns than this is not a point cloud row; the cap bounds the token buffer.
constexpr std::size_t kMaxColumns = 4096;

// A row's fields: split at ';' or ',' when the row has one (CSV), else at runs of blanks.
void split_fields(std::string_view line, std::vector<std::string_view>& out) {
    char delimiter = 0;
    if (line.find(';') != std::string_view::npos) {
        delimiter = ';';
    } else if (line.find(',') != std::string_view::npos) {
        delimiter = ',';
    } else {
        split_blanks(line, out, kMaxColumns + 1);
        return;
    }
    out.clear();
    std::size_t start = 0;
    while (out.size() <= kMaxColumns) {
        const std::size_t end = line.find(delimiter, start);
        out.push_back(trim(line.substr(start, end == std::string_view::npos ? end : end - start)));
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
}

bool same_name(std::string_view a, std::string_view b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](char c, char d) {
        const auto lower = [](char e) { return e >= 'A' && e <= 'Z' ? char(e - 'A' + 'a') : e; };
        return lower(c) == lower(d);
    });
}

// A header cell without CloudCompare's "//" and CSV quotes.
std::string_view column_name(std::string_view cell) {
    if (cell.starts_with("//")) cell.remove_prefix(2);
    if (cell.size() >= 2 && (cell.front() == '"' || cell.front() == '\'') &&
        cell.back() == cell.front()) {
        cell = cell.substr(1, cell.size() - 2);
    }
    return trim(cell);
}

struct Columns {
    std::array<std::size_t, 3> xyz{0, 1, 2};
    std::optional<std::size_t> label;
    std::optional<std::array<std::size_t, 3>> normals;  // all three or none
    [[nodiscard]] std::size_t needed() const {
        std::size_t last = std::max({xyz[0], xyz[1], xyz[2], label.value_or(0)});
        if (normals) last = std::max({last, (*normals)[0], (*normals)[1], (*normals)[2]});
        return last + 1;
    }
};

// The columns a header row names, if it names x, y and z.
std::optional<Columns> header_columns(const std::vector<std::string_view>& cells,
                                      const ReadOptions& options) {
    static constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};
    static constexpr std::array<std::string_view, 3> kNormals{"nx", "ny", "nz"};
    Columns c;
    std::array<bool, 3> found{false, false, false};
    std::array<std::optional<std::size_t>, 3> normal;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const std::string_view name = column_name(cells[i]);
        for (std::size_t a = 0; a < 3; ++a) {
            if (!found[a] && same_name(name, kAxes[a])) {
                found[a] = true;
                c.xyz[a] = i;
            }
            if (options.read_normals && !normal[a] && same_name(name, kNormals[a])) normal[a] = i;
        }
        if (options.read_labels && !c.label && same_name(name, options.label_field)) c.label = i;
    }
    if (!found[0] || !found[1] || !found[2]) return std::nullopt;
    if (normal[0] && normal[1] && normal[2]) {
        c.normals = std::array<std::size_t, 3>{*normal[0], *normal[1], *normal[2]};
    }
    return c;
}

std::size_t count_numbers(const std::vector<std::string_view>& cells) {
    std::size_t n = 0;
    double v = 0;
    for (std::string_view c : cells) n += parse_double(c, v) ? 1 : 0;
    return n;
}

}  // namespace

PointCloud read_text_cloud(std::string_view bytes, std::string_view source,
                           const ReadOptions& options) {
    if (bytes.empty()) throw_malformed(source, "the file is empty");
    PointCloud cloud;
    // Rows take at least 6 bytes ("0 0 0\n"); most take 20 or more. Growth handles the rest.
    cloud.points.reserve(std::min<std::size_t>(bytes.size() / 20, std::size_t{1} << 24));
    PointBuilder builder(cloud, true);

    LineReader lines(bytes);
    std::string_view line;
    std::vector<std::string_view> cells;
    std::optional<Columns> columns;
    bool before_points = true;
    bool may_be_count = true;  // only the first line
    bool header_seen = false;
    while (lines.next(line)) {
        if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) {
            line = line.substr(0, hash);
        }
        line = trim(line);
        if (line.empty()) continue;
        const std::size_t n = lines.line_number();
        split_fields(line, cells);
        if (cells.size() > kMaxColumns) {
            throw_malformed_line(source, n,
                                 cat({"more than ", count_str(kMaxColumns), " columns"}));
        }
        if (before_points) {
            uint64_t count = 0;
            if (may_be_count && cells.size() == 1 && parse_uint(cells[0], count)) {
                may_be_count = false;
                continue;
            }
            may_be_count = false;
            const std::size_t numbers = count_numbers(cells);
            if (!header_seen && numbers < 3) {
                header_seen = true;
                columns = header_columns(cells, options);
                continue;
            }
            if (!columns) {
                // x, y, z are the first three numeric columns of the first point's row.
                if (numbers < 3) {
                    throw_malformed_line(
                        source, n,
                        cat({"expected three numbers (x y z), found ", count_str(numbers)}));
                }
                Columns c;
                std::size_t a = 0;
                double v = 0;
                for (std::size_t i = 0; i < cells.size() && a < 3; ++i) {
                    if (parse_double(cells[i], v)) c.xyz[a++] = i;
                }
                columns = c;
            }
            before_points = false;
            if (columns->label) cloud.labels.reserve(cloud.points.capacity());
            if (columns->normals) cloud.normals.reserve(cloud.points.capacity());
        }
        if (cells.size() < columns->needed()) {
            throw_malformed_line(source, n,
                                 cat({"expected at least ", count_str(columns->needed()),
                                      " values, found ", count_str(cells.size())}));
        }
        double xyz[3];
        for (std::size_t a = 0; a < 3; ++a) {
            const std::string_view cell = cells[columns->xyz[a]];
            if (!parse_double(cell, xyz[a])) {
                throw_malformed_line(source, n,
                                     cat({quoted(cell), " in column ",
                                          count_str(columns->xyz[a] + 1), " is not a number"}));
            }
        }
        if (columns->normals) {
            Vec3f normal = Vec3f::Zero();
            for (std::size_t a = 0; a < 3; ++a) {
                const std::size_t column = (*columns->normals)[a];
                // Straight to float: the writer's shortest text comes back exactly.
                if (!parse_float(cells[column], normal[static_cast<int>(a)])) {
                    throw_malformed_line(source, n,
                                         cat({"normal ", quoted(cells[column]), " in column ",
                                              count_str(column + 1), " is not a number"}));
                }
            }
            cloud.normals.push_back(normal);
        }
        if (columns->label) {
            const std::string_view cell = cells[*columns->label];
            double v = 0;
            int32_t label = 0;
            if (!parse_double(cell, v) || !label_from_double(v, label)) {
                throw_malformed_line(source, n,
                                     cat({"label ", quoted(cell), " is not a 32-bit integer"}));
            }
            cloud.labels.push_back(label);
        }
        builder.add(xyz[0], xyz[1], xyz[2]);
    }
    if (cloud.empty()) throw_malformed(source, "the file holds no points");
    return cloud;
}

void write_text_cloud(std::ostream& out, const CloudView& cloud, char delimiter, bool write_labels,
                      bool count_line, bool write_normals) {
    const CloudLayout layout = layout_for(cloud, write_labels, write_normals);
    OutputBuffer buf(out);
    if (count_line) buf.append(cat({std::to_string(cloud.size()), "\n"}));
    if (layout.normals || layout.labels) {
        const char d[1] = {delimiter};
        const std::string_view sep(d, 1);
        buf.append(cat({"x", sep, "y", sep, "z"}));
        if (layout.normals) buf.append(cat({sep, "nx", sep, "ny", sep, "nz"}));
        if (layout.labels) buf.append(cat({sep, "label"}));
        buf.put('\n');
    }
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            if (a > 0) buf.put(delimiter);
            if (layout.doubles) {
                buf.put_number(absolute_point(cloud, i)[a]);
            } else {
                buf.put_number(cloud.points[i][a]);
            }
        }
        if (layout.normals) {
            for (int a = 0; a < 3; ++a) {
                buf.put(delimiter);
                buf.put_number(cloud.normals[i][a]);
            }
        }
        if (layout.labels) {
            buf.put(delimiter);
            buf.put_number(cloud.labels[i]);
        }
        buf.put('\n');
    }
    buf.flush();
}

}  // namespace surfgrow::io
