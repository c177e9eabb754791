// Reading PLY: header, then each element in order; only the vertex element's x, y, z, normals,
// label (and a fused cloud's scan index with the scan origins from the header) kept.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "surfgrow/io/ascii_scan.hpp"
#include "surfgrow/io/binary_columns.hpp"
#include "surfgrow/io/io_error.hpp"
#include "surfgrow/io/ply.hpp"
#include "surfgrow/io/point_builder.hpp"
#include "surfgrow/io/scalar_type.hpp"

namespace surfgrow::io {

namespace {

// A header longer than this is not a PLY header (it is a few hundred bytes in practice).
constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;
constexpr std::size_t kMaxHeaderLine = std::size_t{1} << 16;

struct Property {
    std::string_view name;  // views into the file's bytes, which outlive the header
    ScalarType type = ScalarType::kFloat32;
    bool is_list = false;
    ScalarType count_type = ScalarType::kUInt8;
};

struct Element {
    std::string_view name;
    uint64_t count = 0;
    std::vector<Property> props;
    [[nodiscard]] bool has_lists() const {
        for (const Property& p : props) {
            if (p.is_list) return true;
        }
        return false;
    }
    // Bytes of one record without lists, or the least a record with lists can take.
    [[nodiscard]] uint64_t min_record_size() const {
        uint64_t size = 0;
        for (const Property& p : props) size += scalar_size(p.is_list ? p.count_type : p.type);
        return size;
    }
};

struct Header {
    PlyEncoding encoding = PlyEncoding::kAscii;
    std::vector<Element> elements;
    std::vector<Vec3d> scan_origins;  // "comment surfgrow scan_origin k x y z", file coordinates
    std::size_t body_offset = 0;
    std::size_t body_first_line = 0;
};

std::string plural(uint64_t n, std::string_view one, std::string_view many) {
    return cat({count_str(n), " ", n == 1 ? one : many});
}

// "comment surfgrow scan_origin k x y z": origin k of a fused cloud, ids 0, 1, 2, ... in order.
void parse_scan_origin(const std::vector<std::string_view>& tok, std::vector<Vec3d>& origins,
                       std::string_view src, std::size_t line) {
    uint64_t k = 0;
    Vec3d o;
    if (tok.size() != 7 || !parse_uint(tok[3], k) || !parse_double(tok[4], o.x()) ||
        !parse_double(tok[5], o.y()) || !parse_double(tok[6], o.z()) || !o.allFinite()) {
        throw_malformed_line(src, line, "expected 'comment surfgrow scan_origin <k> <x> <y> <z>'");
    }
    if (k != origins.size()) {
        throw_malformed_line(src, line,
                             cat({"scan origin ", count_str(k), " where ",
                                  count_str(origins.size()), " was expected"}));
    }
    origins.push_back(o);
}

Header parse_header(std::string_view bytes, std::string_view src) {
    LineReader lines(bytes);
    std::string_view line;
    if (!lines.next(line) || trim(line) != "ply") {
        throw_malformed(src, "not a PLY file (the first line is not 'ply')");
    }
    Header h;
    bool have_format = false;
    std::vector<std::string_view> tok;
    while (true) {
        if (lines.offset() > kMaxHeaderBytes) {
            throw_malformed(src, "no end_header in the first MiB; not a PLY header");
        }
        if (!lines.next(line)) {
            throw_malformed(src, "the header ends before end_header (truncated file?)");
        }
        const std::size_t n = lines.line_number();
        if (line.size() > kMaxHeaderLine) {
            throw_malformed(src, cat({"header line ", count_str(n), " is too long"}));
        }
        split_blanks(line, tok);
        if (tok.empty()) continue;
        const std::string_view kw = tok[0];
        if (kw == "comment" && tok.size() > 2 && tok[1] == "surfgrow" && tok[2] == "scan_origin") {
            parse_scan_origin(tok, h.scan_origins, src, n);
            continue;
        }
        if (kw == "comment" || kw == "obj_info") continue;
        if (kw == "end_header") break;
        if (kw == "format") {
            if (have_format) throw_malformed_line(src, n, "a second format line");
            if (tok.size() != 3) {
                throw_malformed_line(src, n, "expected 'format <encoding> 1.0'");
            }
            if (tok[1] == "ascii") {
                h.encoding = PlyEncoding::kAscii;
            } else if (tok[1] == "binary_little_endian") {
                h.encoding = PlyEncoding::kBinaryLittleEndian;
            } else if (tok[1] == "binary_big_endian") {
                h.encoding = PlyEncoding::kBinaryBigEndian;
            } else {
                throw_malformed_line(src, n, cat({"unknown PLY encoding ", quoted(tok[1])}));
            }
            have_format = true;
        } else if (kw == "element") {
            uint64_t count = 0;
            if (tok.size() != 3 || !parse_uint(tok[2], count)) {
                throw_malformed_line(src, n, "expected 'element <name> <count>' with a count >= 0");
            }
            h.elements.push_back({tok[1], count, {}});
        } else if (kw == "property") {
            if (h.elements.empty()) throw_malformed_line(src, n, "a property before any element");
            Property p;
            if (tok.size() == 5 && tok[1] == "list") {
                const auto ct = ply_scalar_type(tok[2]);
                const auto it = ply_scalar_type(tok[3]);
                if (!ct || !is_integer(*ct) || !it) {
                    throw_malformed_line(
                        src, n,
                        cat({"bad list types ", quoted(tok[2]), " ", quoted(tok[3]),
                             " (the count must be an integer type)"}));
                }
                p = {tok[4], *it, true, *ct};
            } else if (tok.size() == 3) {
                const auto t = ply_scalar_type(tok[1]);
                if (!t)
                    throw_malformed_line(src, n, cat({"unknown property type ", quoted(tok[1])}));
                p = {tok[2], *t, false, ScalarType::kUInt8};
            } else {
                throw_malformed_line(src, n,
                                     "expected 'property <type> <name>' or "
                                     "'property list <count type> <item type> <name>'");
            }
            h.elements.back().props.push_back(p);
        } else {
            throw_malformed_line(src, n, cat({"unknown header keyword ", quoted(kw)}));
        }
    }
    if (!have_format) throw_malformed(src, "the header has no format line");
    h.body_offset = lines.offset();
    h.body_first_line = lines.line_number() + 1;
    return h;
}

constexpr std::array<std::string_view, 3> kAxisNames{"x", "y", "z"};
constexpr std::array<std::string_view, 3> kNormalNames{"nx", "ny", "nz"};

// Which property of the vertex element feeds what.
struct VertexLayout {
    std::array<int, 3> xyz{-1, -1, -1};
    std::array<int, 3> normal{-1, -1, -1};  // all three or none
    int label = -1;
    int scan = -1;  // only read when the header gives scan origins
    [[nodiscard]] bool has_normals() const { return normal[0] >= 0; }
    // Whether property k feeds anything.
    [[nodiscard]] bool uses(int k) const {
        return k == xyz[0] || k == xyz[1] || k == xyz[2] || k == normal[0] || k == normal[1] ||
               k == normal[2] || k == label || k == scan;
    }
};

VertexLayout vertex_layout(const Element& vertex, std::string_view src, const ReadOptions& options,
                           bool want_scan) {
    VertexLayout v;
    for (std::size_t i = 0; i < vertex.props.size(); ++i) {
        const Property& p = vertex.props[i];
        for (int a = 0; a < 3; ++a) {
            if (p.name == kAxisNames[a] && v.xyz[a] < 0) {
                if (p.is_list) {
                    throw_malformed(src, cat({"vertex property ", p.name, " is a list"}));
                }
                v.xyz[a] = static_cast<int>(i);
            }
        }
        if (options.read_labels && !p.is_list && p.name == options.label_field && v.label < 0) {
            v.label = static_cast<int>(i);
        }
        if (want_scan && !p.is_list && p.name == "scan" && v.scan < 0) v.scan = static_cast<int>(i);
        for (int a = 0; a < 3; ++a) {
            // The first property of each name decides; a list one means no normals (below).
            if (options.read_normals && p.name == kNormalNames[a] && v.normal[a] == -1) {
                v.normal[a] = p.is_list ? -2 : static_cast<int>(i);
            }
        }
    }
    for (int a = 0; a < 3; ++a) {
        if (v.xyz[a] < 0) {
            throw_malformed(src, cat({"the vertex element has no ", kAxisNames[a], " property"}));
        }
    }
    // Normals only when all three are plain scalars.
    if (v.normal[0] < 0 || v.normal[1] < 0 || v.normal[2] < 0) v.normal = {-1, -1, -1};
    return v;
}

// A scan index as read: a whole number in [0, 2^32).
bool scan_from_double(double v, uint32_t& out) {
    if (!(v >= 0 && v <= 4294967295.0) || v != std::floor(v)) return false;
    out = static_cast<uint32_t>(v);
    return true;
}

void push_scan(PointCloud& cloud, double value, uint64_t i, std::string_view src) {
    uint32_t k = 0;
    if (!scan_from_double(value, k)) {
        throw_malformed(
            src, cat({"vertex ", count_str(i), " has scan ", num(value), ", not a scan number"}));
    }
    cloud.scan_index.push_back(k);
}

bool wide_coordinates(const Element& vertex, const VertexLayout& v) {
    for (int a = 0; a < 3; ++a) {
        if (is_wide(vertex.props[static_cast<std::size_t>(v.xyz[a])].type)) return true;
    }
    return false;
}

// ---- binary ----------------------------------------------------------------------------------

class BinaryBody {
  public:
    BinaryBody(std::string_view bytes, std::size_t pos, bool swap, std::string_view src)
        : bytes_(bytes), pos_(pos), swap_(swap), src_(src) {}

    [[nodiscard]] std::size_t pos() const { return pos_; }

    void skip(const Element& e) {
        if (!e.has_lists()) {
            pos_ += fixed_block(e, cat({e.name, " elements"}));
            return;
        }
        // Each record takes at least one byte (its first list's count), so this loop ends with
        // the data however large the header's count is.
        for (uint64_t i = 0; i < e.count; ++i) {
            for (const Property& p : e.props) skip_property(e, i, p);
        }
    }

    void read_vertices(const Element& e, const VertexLayout& v, PointCloud& cloud) {
        if (!e.has_lists()) {
            uint64_t offset = 0;
            std::vector<uint64_t> prop_offset;
            for (const Property& p : e.props) {
                prop_offset.push_back(offset);
                offset += scalar_size(p.type);
            }
            const std::size_t base = pos_;
            pos_ += fixed_block(e, "vertices");
            std::array<Column, 3> xyz;
            for (int a = 0; a < 3; ++a) {
                const auto i = static_cast<std::size_t>(v.xyz[a]);
                xyz[a] = {base + prop_offset[i], offset, e.props[i].type};
            }
            Column label;
            if (v.label >= 0) {
                const auto i = static_cast<std::size_t>(v.label);
                label = {base + prop_offset[i], offset, e.props[i].type};
            }
            std::array<Column, 3> normals;
            for (int a = 0; a < 3 && v.has_normals(); ++a) {
                const auto i = static_cast<std::size_t>(v.normal[a]);
                normals[a] = {base + prop_offset[i], offset, e.props[i].type};
            }
            read_columns(bytes_.data(), e.count, xyz, v.label >= 0 ? &label : nullptr,
                         v.has_normals() ? &normals : nullptr, swap_, src_, cloud);
            if (v.scan >= 0) {
                const auto k = static_cast<std::size_t>(v.scan);
                cloud.scan_index.reserve(e.count);
                for (uint64_t i = 0; i < e.count; ++i) {
                    const char* at = bytes_.data() + base + prop_offset[k] + i * offset;
                    push_scan(cloud, load_as_double(at, e.props[k].type, swap_), i, src_);
                }
            }
            return;
        }
        // Lists inside vertices (rare): walk record by record.
        check_fits(e, e.min_record_size(), "vertices");
        cloud.points.reserve(e.count);
        if (v.label >= 0) cloud.labels.reserve(e.count);
        if (v.has_normals()) cloud.normals.reserve(e.count);
        PointBuilder builder(cloud, wide_coordinates(e, v));
        for (uint64_t i = 0; i < e.count; ++i) {
            double xyz[3] = {0, 0, 0};
            Vec3f normal = Vec3f::Zero();
            for (std::size_t k = 0; k < e.props.size(); ++k) {
                const Property& p = e.props[k];
                if (p.is_list) {
                    skip_property(e, i, p);
                    continue;
                }
                const char* at = take(e, i, scalar_size(p.type));
                const auto ik = static_cast<int>(k);
                for (int a = 0; a < 3; ++a) {
                    if (ik == v.xyz[a]) xyz[a] = load_as_double(at, p.type, swap_);
                    if (ik == v.normal[a]) {
                        normal[a] = static_cast<float>(load_as_double(at, p.type, swap_));
                    }
                }
                if (ik == v.label) {
                    int32_t label = 0;
                    const double value = load_as_double(at, p.type, swap_);
                    if (!label_from_double(value, label)) {
                        throw_malformed(src_, cat({"vertex ", count_str(i), " has label ",
                                                   num(value), ", not a 32-bit integer"}));
                    }
                    cloud.labels.push_back(label);
                }
                if (ik == v.scan) push_scan(cloud, load_as_double(at, p.type, swap_), i, src_);
            }
            if (v.has_normals()) cloud.normals.push_back(normal);
            builder.add(xyz[0], xyz[1], xyz[2]);
        }
    }

  private:
    [[nodiscard]] std::size_t left() const { return bytes_.size() - pos_; }

    // Checks that count records of `record` bytes fit in what is left.
    uint64_t check_fits(const Element& e, uint64_t record, std::string_view what) const {
        uint64_t need = 0;
        if (!checked_mul(e.count, record, need) || need > left()) {
            throw_malformed(src_, cat({"header says ", count_str(e.count), " ", what, " of ",
                                       plural(record, "byte", "bytes"), " but only ",
                                       count_str(left()), " bytes follow"}));
        }
        return need;
    }
    std::size_t fixed_block(const Element& e, std::string_view what) const {
        return static_cast<std::size_t>(check_fits(e, e.min_record_size(), what));
    }

    // The next `size` bytes of record i of e.
    const char* take(const Element& e, uint64_t i, uint64_t size) {
        if (size > left()) {
            throw_malformed(src_, cat({"the data ends inside ", e.name, " ", count_str(i), " of ",
                                       count_str(e.count), " (truncated file?)"}));
        }
        const char* at = bytes_.data() + pos_;
        pos_ += static_cast<std::size_t>(size);
        return at;
    }

    void skip_property(const Element& e, uint64_t i, const Property& p) {
        if (!p.is_list) {
            take(e, i, scalar_size(p.type));
            return;
        }
        const double n = load_as_double(take(e, i, scalar_size(p.count_type)), p.count_type, swap_);
        if (n < 0) {
            throw_malformed(src_, cat({e.name, " ", count_str(i), " has a list of ", num(n),
                                       " items in ", p.name}));
        }
        // Counts of 2^63 and more (uint64 lists) cannot fit anyway; avoid converting them.
        const uint64_t items = n < 9.2e18 ? static_cast<uint64_t>(n) : UINT64_MAX;
        uint64_t size = 0;
        if (!checked_mul(items, scalar_size(p.type), size)) size = UINT64_MAX;
        take(e, i, size);
    }

    std::string_view bytes_;
    std::size_t pos_;
    bool swap_;
    std::string_view src_;
};

// ---- ascii -----------------------------------------------------------------------------------

class AsciiBody {
  public:
    AsciiBody(std::string_view text, std::size_t first_line, std::string_view src)
        : tokens_(text, first_line), size_(text.size()), src_(src) {}

    void skip(const Element& e) {
        if (!e.has_lists()) {
            uint64_t n = 0;
            if (!checked_mul(e.count, e.props.size(), n)) n = UINT64_MAX;
            // Ends at the end of the text whatever n is.
            for (uint64_t k = 0; k < n; ++k) next(e, k / e.props.size());
            return;
        }
        for (uint64_t i = 0; i < e.count; ++i) {
            for (const Property& p : e.props) skip_property(e, i, p);
        }
    }

    void read_vertices(const Element& e, const VertexLayout& v, PointCloud& cloud) {
        // Every value takes at least two bytes (a digit and a separator): reserve no more
        // vertices than the text can hold, whatever the header claims.
        const uint64_t fit = size_ / e.props.size() / 2 + 1;
        cloud.points.reserve(std::min(e.count, fit));
        if (v.label >= 0) cloud.labels.reserve(std::min(e.count, fit));
        if (v.has_normals()) cloud.normals.reserve(std::min(e.count, fit));
        PointBuilder builder(cloud, wide_coordinates(e, v));
        for (uint64_t i = 0; i < e.count; ++i) {
            double xyz[3] = {0, 0, 0};
            Vec3f normal = Vec3f::Zero();
            for (std::size_t k = 0; k < e.props.size(); ++k) {
                const Property& p = e.props[k];
                if (p.is_list) {
                    skip_property(e, i, p);
                    continue;
                }
                const auto ik = static_cast<int>(k);
                if (!v.uses(ik)) {
                    next(e, i);
                    continue;
                }
                const std::string_view tok = next(e, i);
                const double value = number(tok, e, i, p);
                for (int a = 0; a < 3; ++a) {
                    if (ik == v.xyz[a]) xyz[a] = value;
                    // Straight to float: the writer's shortest text comes back exactly.
                    if (ik == v.normal[a] && !parse_float(tok, normal[a])) bad_number(tok, e, i, p);
                }
                if (ik == v.label) {
                    int32_t label = 0;
                    if (!label_from_double(value, label)) {
                        throw_malformed_line(
                            src_, tokens_.line_number(),
                            cat({"label ", num(value), " is not a 32-bit integer"}));
                    }
                    cloud.labels.push_back(label);
                }
                if (ik == v.scan) push_scan(cloud, value, i, src_);
            }
            if (v.has_normals()) cloud.normals.push_back(normal);
            builder.add(xyz[0], xyz[1], xyz[2]);
        }
    }

    void check_end() {
        if (!tokens_.at_end()) {
            throw_malformed_line(src_, tokens_.line_number(),
                                 "more data after the last element the header declares");
        }
    }

  private:
    std::string_view next(const Element& e, uint64_t i) {
        std::string_view tok;
        if (!tokens_.next(tok)) {
            throw_malformed(src_, cat({"the data ends inside ", e.name, " ", count_str(i), " of ",
                                       count_str(e.count), " (truncated file?)"}));
        }
        return tok;
    }

    double number(std::string_view tok, const Element& e, uint64_t i, const Property& p) const {
        double value = 0;
        if (!parse_double(tok, value)) bad_number(tok, e, i, p);
        return value;
    }

    [[noreturn]] void bad_number(std::string_view tok, const Element& e, uint64_t i,
                                 const Property& p) const {
        throw_malformed_line(src_, tokens_.line_number(),
                             cat({quoted(tok), " is not a number (", e.name, " ", count_str(i),
                                  ", property ", p.name, ")"}));
    }

    void skip_property(const Element& e, uint64_t i, const Property& p) {
        const std::string_view tok = next(e, i);
        if (!p.is_list) return;
        uint64_t n = 0;
        if (!parse_uint(tok, n)) {
            throw_malformed_line(src_, tokens_.line_number(),
                                 cat({quoted(tok), " is not a list length (", e.name, " ",
                                      count_str(i), ", property ", p.name, ")"}));
        }
        for (uint64_t k = 0; k < n; ++k) next(e, i);
    }

    TokenReader tokens_;
    std::size_t size_;
    std::string_view src_;
};

// Scan origins relative to the cloud's offset; every scan index must name one of them.
void attach_scan_origins(const std::vector<Vec3d>& origins, std::string_view src,
                         PointCloud& cloud) {
    for (std::size_t i = 0; i < cloud.scan_index.size(); ++i) {
        if (cloud.scan_index[i] >= origins.size()) {
            throw_malformed(src, cat({"vertex ", count_str(i), " has scan ",
                                      count_str(cloud.scan_index[i]), " but the header gives ",
                                      plural(origins.size(), "scan origin", "scan origins")}));
        }
    }
    for (const Vec3d& o : origins) cloud.scan_origins.push_back(o - cloud.offset);
    // As fuse_scans does: a single scan's origin is the cloud's viewpoint.
    if (origins.size() == 1) cloud.viewpoint = cloud.scan_origins.front();
}

}  // namespace

PointCloud read_ply(std::string_view bytes, std::string_view source, const ReadOptions& options) {
    if (bytes.empty()) throw_malformed(source, "the file is empty");
    const Header h = parse_header(bytes, source);

    const Element* vertex = nullptr;
    for (const Element& e : h.elements) {
        if (e.name != "vertex") continue;
        if (vertex) throw_malformed(source, "the header declares two vertex elements");
        vertex = &e;
    }
    if (!vertex) throw_malformed(source, "the header declares no vertex element");
    const bool want_scan = options.read_scans && !h.scan_origins.empty();
    const VertexLayout layout = vertex_layout(*vertex, source, options, want_scan);
    if (want_scan && layout.scan < 0) {
        throw_malformed(source, "the header gives scan origins but the vertices have no scan");
    }

    PointCloud cloud;
    if (h.encoding == PlyEncoding::kAscii) {
        AsciiBody body(bytes.substr(h.body_offset), h.body_first_line, source);
        for (const Element& e : h.elements) {
            if (&e == vertex) {
                body.read_vertices(e, layout, cloud);
            } else {
                body.skip(e);
            }
        }
        body.check_end();
    } else {
        const bool big = h.encoding == PlyEncoding::kBinaryBigEndian;
        BinaryBody body(bytes, h.body_offset, big == kHostIsLittleEndian, source);
        for (const Element& e : h.elements) {
            if (&e == vertex) {
                body.read_vertices(e, layout, cloud);
            } else {
                body.skip(e);
            }
        }
        check_padding_tail(bytes, body.pos(), source);
    }
    if (want_scan) attach_scan_origins(h.scan_origins, source, cloud);
    return cloud;
}

}  // namespace surfgrow::io
