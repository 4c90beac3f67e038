// SPDX-License-Identifier: BSD-3-Clause
#include "flow/vtk.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <sstream>

#include "core/number_text.hpp"
#include "flow/hidden_cells.hpp"

namespace imcol::flow {

namespace {

constexpr const char* kByteOrder = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";

std::string file_head(const char* type) {
  return std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"") + type + "\" version=\"1.0\" byte_order=\"" + kByteOrder +
         "\" header_type=\"UInt64\">\n";
}

/// Text safe inside an XML comment or attribute.
std::string xml_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else if (c == '-' && !out.empty() && out.back() == '-') out += ' ', out += c;  // no "--" in a comment
    else out += c;
  }
  return out;
}

template <class T> constexpr const char* vtk_type();
template <> constexpr const char* vtk_type<double>() { return "Float64"; }
template <> constexpr const char* vtk_type<std::int64_t>() { return "Int64"; }
template <> constexpr const char* vtk_type<std::int32_t>() { return "Int32"; }
template <> constexpr const char* vtk_type<std::uint8_t>() { return "UInt8"; }

/// The appended-data block: each array is its byte count (UInt64) followed by its raw bytes; the XML element names
/// its offset into the block.
class Appended {
 public:
  template <class T>
  std::string array(const std::string& name, int components, const std::vector<T>& v) {
    std::ostringstream os;
    os << "<DataArray type=\"" << vtk_type<T>() << "\"";
    if (!name.empty()) os << " Name=\"" << name << "\"";
    if (components > 1) os << " NumberOfComponents=\"" << components << "\"";
    os << " format=\"appended\" offset=\"" << blob_.size() << "\"/>\n";
    const std::uint64_t bytes = v.size() * sizeof(T);
    blob_.append(reinterpret_cast<const char*>(&bytes), sizeof bytes);  // appended, not resized: no zero fill first
    if (bytes) blob_.append(reinterpret_cast<const char*>(v.data()), bytes);
    return os.str();
  }
  const std::string& blob() const { return blob_; }

 private:
  std::string blob_;
};

/// 17 significant digits: a double read back is the same double.
void append_exact(std::string& out, double v) { append_number(out, v, 17); }

/// A point (r, 0, z) of the axisymmetric plane, ASCII.
void append_rz(std::string& out, double r, double z) {
  append_exact(out, r);
  out += " 0 ";
  append_exact(out, z);
  out += '\n';
}

std::string field_number(const char* name, double v) {
  std::string out = std::string("<DataArray type=\"Float64\" Name=\"") + name + "\" NumberOfTuples=\"1\" format=\"ascii\">";
  append_exact(out, v);
  return out + "</DataArray>\n";
}

/// Field data of every file of a snapshot: time_s, and the gaps where there is one (gap_m, gap_D the trajectory's;
/// kernel_gap_m, kernel_gap_D where the kernel holds its spheres; D the first sphere's diameter). Numbers only:
/// meshio refuses string arrays (the label is in each file's comment).
std::string field_data(const SnapshotInfo& in) {
  std::string out = "<FieldData>\n" + field_number("time_s", in.time);
  const SnapshotBodies& b = *in.bodies;
  if (std::isfinite(b.gap()))
    out += field_number("gap_m", b.gap()) + field_number("gap_D", b.gap() / b.diameter()) + field_number("kernel_gap_m", b.kernel_gap()) +
           field_number("kernel_gap_D", b.kernel_gap() / b.diameter());
  return out + "</FieldData>\n";
}

std::string spheres_vtp(const std::vector<SphereState>& sph, const SnapshotInfo& in, const char* which) {
  constexpr int kSegments = 64;  // per semicircle
  const std::size_t n = sph.size();
  std::string pts, conn, offs, diam, vel;
  for (std::size_t b = 0; b < n; ++b) {
    const double a = sph[b].radius, zc = sph[b].z;
    for (int k = 0; k <= kSegments; ++k) {
      const double th = M_PI * k / kSegments;  // from the south pole (r = 0, z = zc − a) round to the north pole
      append_rz(pts, k == 0 || k == kSegments ? 0.0 : a * std::sin(th), zc - a * std::cos(th));
      conn += std::to_string(b * (kSegments + 1) + k) + (k == kSegments ? "\n" : " ");
    }
    offs += std::to_string((b + 1) * (kSegments + 1)) + " ";
    append_exact(diam, 2 * a);
    diam += ' ';
    vel += "0 0 ";
    append_exact(vel, sph[b].u);
    vel += '\n';
  }
  std::ostringstream os;
  os << file_head("PolyData") << "<!-- imcol: the spheres " << which << " at " << xml_text(in.label)
     << "; (x, y, z) = (r, 0, z) m; diameter_m; velocity_m_s (0, 0, u) seen from the same frame as the flow fields -->\n"
     << "<PolyData>\n" << field_data(in) << "<Piece NumberOfPoints=\"" << n * (kSegments + 1)
     << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << n << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
     << "<CellData Scalars=\"diameter_m\" Vectors=\"velocity_m_s\">\n"
     << "<DataArray type=\"Float64\" Name=\"diameter_m\" format=\"ascii\">\n" << diam << "\n</DataArray>\n"
     << "<DataArray type=\"Float64\" Name=\"velocity_m_s\" NumberOfComponents=\"3\" format=\"ascii\">\n" << vel << "</DataArray>\n"
     << "</CellData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n" << pts << "</DataArray>\n</Points>\n"
     << "<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n" << conn << "</DataArray>\n"
     << "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n" << offs << "\n</DataArray>\n</Lines>\n"
     << "</Piece>\n</PolyData>\n</VTKFile>\n";
  return os.str();
}

std::string wall_vtp(const std::vector<LevelFields>& levels, const SnapshotInfo& in) {
  const auto& gc = levels.back().g;
  std::string pts;
  for (double r : {0.0, gc.r(gc.nr)}) append_rz(pts, r, *in.bodies->wall_z);
  std::ostringstream os;
  os << file_head("PolyData") << "<!-- imcol: the no-slip wall at " << xml_text(in.label)
     << "; (x, y, z) = (r, 0, z) m, from the axis to the coarsest level's radius -->\n"
     << "<PolyData>\n" << field_data(in)
     << "<Piece NumberOfPoints=\"2\" NumberOfVerts=\"0\" NumberOfLines=\"1\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
     << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n" << pts << "</DataArray>\n</Points>\n"
     << "<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n0 1\n</DataArray>\n"
     << "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n2\n</DataArray>\n</Lines>\n"
     << "</Piece>\n</PolyData>\n</VTKFile>\n";
  return os.str();
}

/// The point data's arrays: vectors first (their components gathered as (r, 0, z)), then the scalars, in the
/// fields' order; the vectors' names and the first scalar's.
struct PointArrays {
  std::string xml;
  std::vector<std::string> vectors;
  std::string first_scalar;
};

PointArrays point_arrays(const LevelFields& L, Appended& ap) {
  const std::size_t np = L.g.size();
  PointArrays out;
  for (const auto& f : L.fields)
    if (f.component >= 0 && std::find(out.vectors.begin(), out.vectors.end(), f.name) == out.vectors.end()) out.vectors.push_back(f.name);
  for (const auto& name : out.vectors) {
    std::vector<double> v(3 * np, 0.0);
    for (const auto& f : L.fields)
      if (f.name == name)
        for (std::size_t k = 0; k < np; ++k) v[3 * k + 2 * f.component] = f.values[k];  // r → x, z → z
    out.xml += ap.array(name, 3, v);
  }
  for (const auto& f : L.fields)
    if (f.component < 0) {
      if (out.first_scalar.empty()) out.first_scalar = f.name;
      out.xml += ap.array(f.name, 1, f.values);
    }
  return out;
}

/// The vertices as (r, 0, z).
std::vector<double> vertex_xyz(const LevelFields& L) {
  const auto& g = L.g;
  std::vector<double> xyz(3 * g.size(), 0.0);
  for (int i = 0; i <= g.nr; ++i)
    for (int j = 0; j <= g.nz; ++j) {
      const std::size_t k = g.at(i, j);
      xyz[3 * k] = L.r(i);
      xyz[3 * k + 2] = L.z(j);
    }
  return xyz;
}

/// Quads counter-clockwise in (r, z) seen from −y. Int32 indices: a level has far fewer than 2³¹ vertices
/// (flow/cost.hpp refuses grids beyond half the memory).
struct QuadCells {
  std::vector<std::int32_t> conn, offsets;
  std::vector<std::uint8_t> types;
};

QuadCells quad_cells(const LevelGeometry& g) {
  const std::size_t nc = static_cast<std::size_t>(g.nr) * g.nz;
  QuadCells q{std::vector<std::int32_t>(4 * nc), std::vector<std::int32_t>(nc), std::vector<std::uint8_t>(nc, 9)};  // 9: VTK_QUAD
  std::size_t c = 0;
  for (int i = 0; i < g.nr; ++i)
    for (int j = 0; j < g.nz; ++j, ++c) {
      const auto p = static_cast<std::int32_t>(g.at(i, j)), r = static_cast<std::int32_t>(g.at(i + 1, j));
      q.conn[4 * c] = p;
      q.conn[4 * c + 1] = r;
      q.conn[4 * c + 2] = r + 1;
      q.conn[4 * c + 3] = p + 1;
      q.offsets[c] = static_cast<std::int32_t>(4 * (c + 1));
    }
  return q;
}

}  // namespace

std::string level_vtu(const std::vector<LevelFields>& levels, std::size_t level, const SnapshotInfo& in) {
  const LevelFields& L = levels[level];
  const auto& g = L.g;
  const std::size_t np = g.size(), nc = static_cast<std::size_t>(g.nr) * g.nz;
  Appended ap;
  const PointArrays pd = point_arrays(L, ap);
  const QuadCells q = quad_cells(g);
  const CellFlags flags = cell_flags(levels, level, *in.bodies);
  const std::string cell_data = ap.array("level", 1, std::vector<std::uint8_t>(nc, static_cast<std::uint8_t>(level))) +
                                ap.array("finer", 1, flags.finer) + ap.array("vtkGhostType", 1, flags.ghost);
  const std::string points = ap.array("", 3, vertex_xyz(L));
  const std::string cells = ap.array("connectivity", 1, q.conn) + ap.array("offsets", 1, q.offsets) + ap.array("types", 1, q.types);

  std::ostringstream os;
  os << file_head("UnstructuredGrid") << "<!-- imcol: flow fields, level " << level << " (0 the finest, spacing " << std::setprecision(17)
     << g.h << " m), " << xml_text(in.label)
     << "; (x, y, z) = (r, 0, z) m; velocity_m_s (u_r, 0, u_z), stream_function_m3_s (total Stokes streamfunction), vorticity_1_s, "
        "pressure_Pa (p - p_inf); cell data: level, finer = 1 where a finer level covers the cell, vtkGhostType = 32 (hidden) "
        "where a finer level covers the cell or its centre is inside a solid -->\n"
     << "<UnstructuredGrid>\n" << field_data(in) << "<Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n"
     << "<PointData";
  if (!pd.vectors.empty()) os << " Vectors=\"" << pd.vectors.front() << "\"";
  if (!pd.first_scalar.empty()) os << " Scalars=\"" << pd.first_scalar << "\"";
  os << ">\n" << pd.xml << "</PointData>\n<CellData Scalars=\"level\">\n" << cell_data << "</CellData>\n<Points>\n" << points
     << "</Points>\n<Cells>\n" << cells << "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  static constexpr char kTail[] = "\n</AppendedData>\n</VTKFile>\n";
  std::string out = os.str();
  out.reserve(out.size() + ap.blob().size() + sizeof kTail);
  out += ap.blob();
  out += kTail;
  return out;
}

std::vector<NamedText> snapshot_vtk(const Solver& s, const std::vector<LevelFields>& levels, const SnapshotFrame& f,
                                    const std::string& stem, const std::string& label) {
  const SnapshotBodies bodies = snapshot_bodies(s, f);
  const SnapshotInfo in{s.time() + f.t_shift, label, &bodies};
  std::vector<NamedText> out;
  std::ostringstream vtm;
  vtm << file_head("vtkMultiBlockDataSet") << "<!-- imcol: flow fields at " << xml_text(label) << ", t = " << std::setprecision(17)
      << in.time << " s -->\n<vtkMultiBlockDataSet>\n<Block index=\"0\" name=\"levels\">\n";
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const std::string name = stem + "_level" + std::to_string(l) + ".vtu";
    out.push_back({name, level_vtu(levels, l, in)});
    vtm << "<DataSet index=\"" << l << "\" name=\"level " << l << "\" file=\"" << xml_text(name) << "\"/>\n";
  }
  vtm << "</Block>\n<Block index=\"1\" name=\"bodies\">\n";
  out.push_back({stem + "_spheres.vtp", spheres_vtp(bodies.spheres, in, "where the trajectory has them")});
  vtm << "<DataSet index=\"0\" name=\"spheres\" file=\"" << xml_text(out.back().name) << "\"/>\n";
  out.push_back({stem + "_kernel_spheres.vtp", spheres_vtp(bodies.kernel_spheres, in, "where the flow kernel holds them")});
  vtm << "<DataSet index=\"1\" name=\"kernel_spheres\" file=\"" << xml_text(out.back().name) << "\"/>\n";
  if (bodies.wall_z) {
    out.push_back({stem + "_wall.vtp", wall_vtp(levels, in)});
    vtm << "<DataSet index=\"2\" name=\"wall\" file=\"" << xml_text(out.back().name) << "\"/>\n";
  }
  vtm << "</Block>\n</vtkMultiBlockDataSet>\n</VTKFile>\n";
  out.insert(out.begin(), {stem + ".vtm", vtm.str()});
  return out;
}

std::string vtk_series(const std::vector<SeriesEntry>& entries) {
  std::ostringstream os;
  os << file_head("Collection") << "<!-- imcol: flow fields over time (s); each file groups the grid levels and the bodies -->\n<Collection>\n"
     << std::setprecision(17);
  for (const auto& e : entries)
    os << "<DataSet timestep=\"" << e.time << "\" group=\"\" part=\"0\" file=\"" << xml_text(e.file) << "\"/> <!-- " << xml_text(e.label)
       << " -->\n";
  os << "</Collection>\n</VTKFile>\n";
  return os.str();
}

}  // namespace imcol::flow
