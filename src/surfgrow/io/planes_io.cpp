#include "surfgrow/io/planes_io.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/file_bytes.hpp"
#include "surfgrow/io/fixed_ply_header.hpp"
#include "surfgrow/io/json_fields.hpp"
#include "surfgrow/io/output_buffer.hpp"

namespace surfgrow::io {

namespace {

using namespace json_fields;

static_assert(std::endian::native == std::endian::little,
              "binary writers assume a little-endian host");

ordered_json ring_json(const Ring& ring) {
    ordered_json out = ordered_json::array();
    for (const Vec2d& p : ring) out.push_back(ordered_json::array({p.x(), p.y()}));
    return out;
}

Ring ring_of(const json& j, const std::string& what) {
    if (!j.is_array())
        throw std::invalid_argument(cat({what, " is not a list of [a, b] vertices"}));
    if (j.size() < 3)
        throw std::invalid_argument(
            cat({what, " has ", std::to_string(j.size()), " vertices (a ring needs at least 3)"}));
    Ring ring;
    ring.reserve(j.size());
    for (const json& v : j) {
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
            throw std::invalid_argument(cat({what, " has a vertex that is not [a, b]"}));
        const Vec2d p(v[0].get<double>(), v[1].get<double>());
        if (!p.allFinite()) throw std::invalid_argument(cat({what, " has a non-finite vertex"}));
        ring.push_back(p);
    }
    return ring;
}

}  // namespace

void write_planes_json(std::ostream& out, const BoundPlanes& planes, const ResultMeta& meta) {
    const BoundPlaneConfig& c = planes.config;
    const BoundPlaneStats& s = planes.stats;
    const ordered_json head = {
        {"format", "surfgrow-planes"},
        {"version", 1},
        {"units", meta.units},
        {"offset", vec_json(meta.offset)},
        {"input", meta.input},
        {"result_id", meta.result_id},
        {"parameters",
         {{"mu", c.mu},
          {"max_angle_deg", c.max_angle_deg},
          {"max_offset", c.max_offset},
          {"adjacency", c.adjacency},
          {"max_gap", c.max_gap},
          {"resolution", c.resolution},
          {"closing_radius", c.closing_radius},
          {"simplify_tolerance", c.simplify_tolerance}}},
        {"summary",
         {{"planes", planes.planes.size()},
          {"patches", s.patches},
          {"patches_merged", s.patches_merged},
          {"adjacent_pairs", s.adjacent_pairs},
          {"points", s.points},
          {"degenerate", s.degenerate},
          {"area", s.area},
          {"noise", s.noise}}},
    };
    // The head indented, then one plane per line: readable, diffable, and not a line per number.
    std::string text = head.dump(1);
    text.pop_back();  // the closing brace
    while (!text.empty() && text.back() == '\n') text.pop_back();
    OutputBuffer buf(out);
    buf.append(text);
    buf.append(",\n \"planes\": [");
    for (std::size_t k = 0; k < planes.planes.size(); ++k) {
        const BoundPlane& p = planes.planes[k];
        const Vec3d centroid = p.centroid + meta.offset;
        ordered_json polys = ordered_json::array();
        for (const PolygonWithHoles& poly : p.polygons) {
            ordered_json holes = ordered_json::array();
            for (const Ring& h : poly.holes) holes.push_back(ring_json(h));
            polys.push_back({{"outer", ring_json(poly.outer)}, {"holes", holes}});
        }
        const ordered_json row = {
            {"id", k},
            {"plane", {p.normal.x(), p.normal.y(), p.normal.z(), -p.normal.dot(centroid)}},
            {"normal", vec_json(p.normal)},
            {"centroid", vec_json(centroid)},
            {"u_axis", vec_json(p.u_axis)},
            {"v_axis", vec_json(p.v_axis)},
            {"area", p.area},
            {"rms", p.rms},
            {"points", p.point_count},
            {"degenerate", p.degenerate},
            {"closing_radius", p.closing_radius},
            {"bounds",
             {{"min", vec_json(p.bounds.empty() ? centroid : Vec3d(p.bounds.min + meta.offset))},
              {"max", vec_json(p.bounds.empty() ? centroid : Vec3d(p.bounds.max + meta.offset))}}},
            {"patches", p.patches},
            {"polygons", polys},
        };
        buf.append(k ? ",\n  " : "\n  ");
        buf.append(row.dump());
    }
    buf.append(planes.planes.empty() ? "]\n}\n" : "\n ]\n}\n");
    buf.flush();
}

StoredPlanes read_planes_json(const std::filesystem::path& file) {
    const FileBytes bytes = FileBytes::read(file);
    return parse_planes_json(bytes.view(), file.string());
}

StoredPlanes parse_planes_json(std::string_view text, std::string_view source) {
    const std::filesystem::path file(source);
    const json j = parse_text(text, file);
    StoredPlanes r;
    BoundPlanes& bp = r.planes;
    std::string where = "the header";
    try {
        if (!j.is_object() || j.value("format", "") != "surfgrow-planes")
            malformed(file, "not a surfgrow planes file (no \"format\": \"surfgrow-planes\")");
        if (const int version = integer_at<int>(j, "version"); version != 1)
            malformed(file, cat({"version ", std::to_string(version), " is not supported (1 is)"}));
        r.meta.units = string_of(j.at("units"), "units");
        r.meta.offset = vec_of(j.at("offset"), "offset");
        r.meta.input = j.contains("input") ? string_of(j.at("input"), "input") : std::string();
        r.meta.result_id =
            j.contains("result_id") ? string_of(j.at("result_id"), "result_id") : std::string();
        const json& p = j.at("parameters");
        BoundPlaneConfig& c = bp.config;
        c.mu = p.at("mu").get<double>();
        c.max_angle_deg = p.at("max_angle_deg").get<double>();
        c.max_offset = non_negative(p.at("max_offset"), "max_offset");
        c.adjacency = non_negative(p.at("adjacency"), "adjacency");
        c.max_gap = p.at("max_gap").get<double>();
        c.resolution = non_negative(p.at("resolution"), "resolution");
        c.closing_radius = non_negative(p.at("closing_radius"), "closing_radius");
        c.simplify_tolerance = non_negative(p.at("simplify_tolerance"), "simplify_tolerance");
        if (!(c.mu > 0) || !std::isfinite(c.mu)) throw std::invalid_argument("mu must be positive");
        const json& s = j.at("summary");
        bp.stats.patches = integer_at<std::uint64_t>(s, "patches");
        bp.stats.patches_merged = integer_at<std::uint64_t>(s, "patches_merged");
        bp.stats.adjacent_pairs = integer_at<std::uint64_t>(s, "adjacent_pairs");
        bp.stats.points = integer_at<std::uint64_t>(s, "points");
        bp.stats.degenerate = integer_at<std::uint64_t>(s, "degenerate");
        bp.stats.area = s.at("area").get<double>();
        bp.stats.noise = s.at("noise").get<double>();
        if (bp.stats.patches > (std::uint64_t{1} << 31))
            throw std::invalid_argument("the patch count is out of range");
        bp.plane_of_patch.assign(bp.stats.patches, -1);
        const json& list = j.at("planes");
        if (!list.is_array()) throw std::invalid_argument("\"planes\" is not a list");
        if (list.size() != integer_at<std::size_t>(s, "planes"))
            throw std::invalid_argument(
                cat({"the summary says ", s.at("planes").dump(), " planes but ",
                     std::to_string(list.size()), " are listed"}));
        for (std::size_t k = 0; k < list.size(); ++k) {
            where = cat({"plane ", std::to_string(k)});
            const json& jp = list[k];
            BoundPlane plane;
            plane.normal = unit_of(jp.at("normal"), "its normal");
            plane.centroid = vec_of(jp.at("centroid"), "its centroid") - r.meta.offset;
            plane.u_axis = unit_of(jp.at("u_axis"), "its u_axis");
            plane.v_axis = unit_of(jp.at("v_axis"), "its v_axis");
            if (std::abs(plane.u_axis.dot(plane.normal)) > 1e-6 ||
                (plane.normal.cross(plane.u_axis) - plane.v_axis).norm() > 1e-6)
                throw std::invalid_argument("its axes are not normal x u_axis = v_axis");
            plane.area = non_negative(jp.at("area"), "its area");
            plane.rms = non_negative(jp.at("rms"), "its rms");
            plane.point_count = integer_at<std::uint64_t>(jp, "points");
            plane.degenerate = jp.at("degenerate").get<bool>();
            plane.closing_radius = non_negative(jp.at("closing_radius"), "its closing_radius");
            plane.bounds.add(vec_of(jp.at("bounds").at("min"), "its bounds") - r.meta.offset);
            plane.bounds.add(vec_of(jp.at("bounds").at("max"), "its bounds") - r.meta.offset);
            for (const json& id : jp.at("patches")) {
                const auto s_id = integer_of<std::uint64_t>(id, "a patch id");
                if (s_id >= bp.plane_of_patch.size())
                    throw std::invalid_argument(
                        cat({"patch ", std::to_string(s_id), " is beyond the ",
                             std::to_string(bp.stats.patches), " patches"}));
                if (bp.plane_of_patch[s_id] >= 0)
                    throw std::invalid_argument(
                        cat({"patch ", std::to_string(s_id), " is already in plane ",
                             std::to_string(bp.plane_of_patch[s_id])}));
                bp.plane_of_patch[s_id] = static_cast<std::int32_t>(k);
                plane.patches.push_back(static_cast<std::uint32_t>(s_id));
            }
            const json& polys = jp.at("polygons");
            if (!polys.is_array()) throw std::invalid_argument("its polygons are not a list");
            for (std::size_t q = 0; q < polys.size(); ++q) {
                const std::string name = cat({"polygon ", std::to_string(q)});
                PolygonWithHoles poly;
                poly.outer = ring_of(polys[q].at("outer"), cat({name, " outer ring"}));
                const json& holes = polys[q].at("holes");
                if (!holes.is_array())
                    throw std::invalid_argument(cat({name, " holes are not a list"}));
                for (std::size_t h = 0; h < holes.size(); ++h)
                    poly.holes.push_back(
                        ring_of(holes[h], cat({name, " hole ", std::to_string(h)})));
                plane.polygons.push_back(std::move(poly));
            }
            bp.planes.push_back(std::move(plane));
        }
    } catch (const json::exception& e) {
        malformed(file, cat({where, ": missing or mistyped field: ", e.what()}));
    } catch (const std::invalid_argument& e) {
        malformed(file, cat({where, ": ", e.what()}));
    }
    return r;
}

void write_planes_ply(std::ostream& out, const PlaneMesh& mesh, const ResultMeta& meta) {
    const bool wide = meta.offset != Vec3d::Zero();  // keep georeferenced precision
    const char* pos = wide ? "double" : "float";
    std::ostringstream head;
    head << "ply\nformat binary_little_endian 1.0\n"
         << "comment surfgrow bound planes: triangulated boundary polygons, plane id per face\n"
         << "comment units " << meta.units << "\n"
         << "comment result_id " << meta.result_id << "\n"
         << "element vertex " << mesh.vertices.size() << "\n"
         << "property " << pos << " x\nproperty " << pos << " y\nproperty " << pos << " z\n"
         << "property float nx\nproperty float ny\nproperty float nz\nproperty int plane\n"
         << "element face " << mesh.triangles.size() << "\n"
         << "property list uchar uint vertex_indices\nproperty int plane\nend_header\n";
    OutputBuffer buf(out);
    buf.append(head.str());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Vec3d p = mesh.vertices[i] + meta.offset;
        for (int a = 0; a < 3; ++a) {
            if (wide)
                buf.put_binary(p[a], false);
            else
                buf.put_binary(static_cast<float>(p[a]), false);
        }
        const Vec3d& n = mesh.plane_normals[mesh.vertex_plane[i]];
        for (int a = 0; a < 3; ++a) buf.put_binary(static_cast<float>(n[a]), false);
        buf.put_binary(static_cast<std::int32_t>(mesh.vertex_plane[i]), false);
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        buf.put_binary(std::uint8_t{3}, false);
        for (const std::uint32_t v : mesh.triangles[t]) buf.put_binary(v, false);
        buf.put_binary(static_cast<std::int32_t>(mesh.triangle_plane[t]), false);
    }
    buf.flush();
}

void write_planes_obj(std::ostream& out, const PlaneMesh& mesh, const ResultMeta& meta) {
    OutputBuffer buf(out);
    buf.append("# surfgrow bound planes: triangulated boundary polygons\n# units ");
    buf.append(meta.units);
    buf.append("\n");
    for (const Vec3d& n : mesh.plane_normals) {
        buf.append("vn");
        for (int a = 0; a < 3; ++a) {
            buf.put(' ');
            buf.put_number(n[a]);
        }
        buf.put('\n');
    }
    for (const Vec3d& v : mesh.vertices) {
        buf.append("v");
        for (int a = 0; a < 3; ++a) {
            buf.put(' ');
            buf.put_number(v[a] + meta.offset[a]);
        }
        buf.put('\n');
    }
    std::int64_t current = -1;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const std::uint32_t plane = mesh.triangle_plane[t];
        if (plane != current) {
            current = plane;
            buf.append("o plane_");
            buf.put_number(plane);
            buf.put('\n');
        }
        buf.put('f');
        for (const std::uint32_t v : mesh.triangles[t]) {  // OBJ counts from 1
            buf.put(' ');
            buf.put_number(v + 1);
            buf.append("//");
            buf.put_number(plane + 1);
        }
        buf.put('\n');
    }
    buf.flush();
}

void write_planes_ply(std::ostream& out, const BoundPlanes& planes, const ResultMeta& meta) {
    write_planes_ply(out, mesh_bound_planes(planes), meta);
}

void write_planes_obj(std::ostream& out, const BoundPlanes& planes, const ResultMeta& meta) {
    write_planes_obj(out, mesh_bound_planes(planes), meta);
}

PlaneMesh read_planes_ply(const std::filesystem::path& file, const Vec3d& offset) {
    const FileBytes bytes = FileBytes::read(file);
    return parse_planes_ply(bytes.view(), file.string(), offset);
}

PlaneMesh parse_planes_ply(std::string_view all, std::string_view source, const Vec3d& offset) {
    const std::filesystem::path file(source);
    const FixedPlyHeader h = read_fixed_ply_header(all, source);
    const bool wide = h.positions_in_double();
    const std::string t = wide ? "double" : "float";
    const std::vector<std::string> expected = {
        "element vertex", t + " x",   t + " y",    t + " z",       "float nx",
        "float ny",       "float nz", "int plane", "element face", "list uchar uint vertex_indices",
        "int plane"};
    if (!h.binary_little_endian || h.layout != expected)
        malformed(file,
                  "not a surfgrow planes mesh (expected the layout planes.ply is written in)");
    const std::uint64_t vertices = h.elements[0].second, faces = h.elements[1].second;
    const std::size_t vsize = (wide ? 24 : 12) + 16, fsize = 1 + 12 + 4;
    const std::size_t body = h.body;
    if (vertices > all.size() / vsize || faces > all.size() / fsize ||
        all.size() - body != vertices * vsize + faces * fsize)
        malformed(file,
                  cat({"truncated or too long: the header promises ", std::to_string(vertices),
                       " vertices and ", std::to_string(faces), " faces"}));
    const char* p = all.data() + body;
    auto take = [&p](auto& v) {
        std::memcpy(&v, p, sizeof v);
        p += sizeof v;
    };
    PlaneMesh mesh;
    std::int64_t planes = 0;
    for (std::size_t i = 0; i < vertices; ++i) {
        Vec3d v;
        for (int a = 0; a < 3; ++a) {
            if (wide) {
                double x;
                take(x);
                v[a] = x;
            } else {
                float x;
                take(x);
                v[a] = x;
            }
        }
        float n[3];
        for (float& x : n) take(x);
        std::int32_t plane;
        take(plane);
        if (!v.allFinite() || plane < 0)
            malformed(file, cat({"vertex ", std::to_string(i), " is not finite or has no plane"}));
        // The plane normals are indexed by id: an id beyond the file's size would make the
        // reader allocate for planes no file of this size can describe.
        if (static_cast<std::uint64_t>(plane) >= all.size())
            malformed(file, cat({"vertex ", std::to_string(i), " has plane ", std::to_string(plane),
                                 ", more planes than the file could hold"}));
        mesh.vertices.push_back(v - offset);
        mesh.vertex_plane.push_back(static_cast<std::uint32_t>(plane));
        if (plane >= planes) {
            mesh.plane_normals.resize(static_cast<std::size_t>(plane) + 1, Vec3d::Zero());
            planes = plane + 1;
        }
        mesh.plane_normals[static_cast<std::size_t>(plane)] = Vec3d(n[0], n[1], n[2]);
    }
    for (std::size_t f = 0; f < faces; ++f) {
        std::uint8_t count;
        take(count);
        std::array<std::uint32_t, 3> tri;
        for (std::uint32_t& v : tri) take(v);
        std::int32_t plane;
        take(plane);
        if (count != 3) malformed(file, cat({"face ", std::to_string(f), " is not a triangle"}));
        for (const std::uint32_t v : tri)
            if (v >= vertices)
                malformed(file, cat({"face ", std::to_string(f), " refers to vertex ",
                                     std::to_string(v), " of ", std::to_string(vertices)}));
        if (plane < 0 || plane >= planes)
            malformed(file, cat({"face ", std::to_string(f), " has plane ", std::to_string(plane),
                                 " which no vertex has"}));
        mesh.triangles.push_back(tri);
        mesh.triangle_plane.push_back(static_cast<std::uint32_t>(plane));
    }
    return mesh;
}

}  // namespace surfgrow::io
