#include "gauss/mesh/mesh_io.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gauss {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw std::runtime_error("cannot read mesh '" + path + "': " + why);
}

void add_polygon(const std::vector<int64_t>& poly, TriangleMesh& m) {
  for (size_t i = 1; i + 1 < poly.size(); ++i) {
    m.F.push_back(poly[0]);
    m.F.push_back(poly[i]);
    m.F.push_back(poly[i + 1]);
  }
}

TriangleMesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "file not found or not readable");
  TriangleMesh m;
  std::string line;
  std::vector<int64_t> poly;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") {
      double x, y, z;
      if (!(ss >> x >> y >> z)) fail(path, "bad vertex line: " + line);
      m.V.insert(m.V.end(), {x, y, z});
    } else if (tag == "f") {
      poly.clear();
      std::string tok;
      while (ss >> tok) {
        const int64_t idx = std::stoll(tok.substr(0, tok.find('/')));
        const int64_t nv = static_cast<int64_t>(m.V.size() / 3);
        poly.push_back(idx < 0 ? nv + idx : idx - 1);
      }
      if (poly.size() < 3) fail(path, "face with fewer than 3 vertices: " + line);
      add_polygon(poly, m);
    }
  }
  return m;
}

size_t type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

double read_binary(std::istream& in, const std::string& t, bool swap) {
  unsigned char buf[8];
  const size_t n = type_size(t);
  in.read(reinterpret_cast<char*>(buf), n);
  if (swap) std::reverse(buf, buf + n);
  if (t == "char" || t == "int8") return static_cast<int8_t>(buf[0]);
  if (t == "uchar" || t == "uint8") return buf[0];
  if (t == "short" || t == "int16") { int16_t v; std::memcpy(&v, buf, 2); return v; }
  if (t == "ushort" || t == "uint16") { uint16_t v; std::memcpy(&v, buf, 2); return v; }
  if (t == "int" || t == "int32") { int32_t v; std::memcpy(&v, buf, 4); return v; }
  if (t == "uint" || t == "uint32") { uint32_t v; std::memcpy(&v, buf, 4); return v; }
  if (t == "float" || t == "float32") { float v; std::memcpy(&v, buf, 4); return v; }
  double v;
  std::memcpy(&v, buf, 8);
  return v;
}

struct PlyProperty {
  std::string name, type, count_type;  // count_type non-empty for lists
};
struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> props;
};

TriangleMesh read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "file not found or not readable");
  std::string line, format;
  std::vector<PlyElement> elements;
  std::getline(in, line);
  if (line.rfind("ply", 0) != 0) fail(path, "missing 'ply' magic");
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "format") ss >> format;
    else if (tag == "element") {
      PlyElement e;
      ss >> e.name >> e.count;
      elements.push_back(e);
    } else if (tag == "property") {
      if (elements.empty()) fail(path, "property before element");
      PlyProperty p;
      std::string t;
      ss >> t;
      if (t == "list") ss >> p.count_type >> p.type >> p.name;
      else { p.type = t; ss >> p.name; }
      if (type_size(p.type) == 0) fail(path, "unknown property type " + p.type);
      elements.back().props.push_back(p);
    } else if (tag == "end_header") break;
  }
  const bool ascii = format == "ascii";
  const bool swap = format == "binary_big_endian";
  if (!ascii && format != "binary_little_endian" && !swap) fail(path, "unknown format " + format);
  TriangleMesh m;
  std::vector<int64_t> poly;
  for (const PlyElement& e : elements) {
    for (size_t i = 0; i < e.count; ++i) {
      std::istringstream row;
      if (ascii) {
        if (!std::getline(in, line)) fail(path, "file ends early");
        row.str(line);
      }
      auto next = [&](const std::string& type) -> double {
        if (!ascii) return read_binary(in, type, swap);
        double v;
        if (!(row >> v)) fail(path, "short row in element " + e.name);
        return v;
      };
      double xyz[3] = {0, 0, 0};
      for (const PlyProperty& p : e.props) {
        if (!p.count_type.empty()) {
          const size_t n = static_cast<size_t>(next(p.count_type));
          poly.clear();
          for (size_t k = 0; k < n; ++k) poly.push_back(static_cast<int64_t>(next(p.type)));
          if (e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index")) {
            if (poly.size() < 3) fail(path, "face with fewer than 3 vertices");
            add_polygon(poly, m);
          }
        } else {
          const double v = next(p.type);
          if (e.name == "vertex") {
            if (p.name == "x") xyz[0] = v;
            if (p.name == "y") xyz[1] = v;
            if (p.name == "z") xyz[2] = v;
          }
        }
      }
      if (e.name == "vertex") m.V.insert(m.V.end(), xyz, xyz + 3);
      if (!in && !ascii) fail(path, "file ends early");
    }
  }
  return m;
}

}  // namespace

TriangleMesh read_mesh(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (ext == "obj") return read_obj(path);
  if (ext == "ply") return read_ply(path);
  fail(path, "unsupported extension (use .obj or .ply)");
}

void write_obj(const std::string& path, const TriangleMesh& m) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  out.precision(17);
  for (int v = 0; v < m.num_vertices(); ++v)
    out << "v " << m.V[3 * v] << ' ' << m.V[3 * v + 1] << ' ' << m.V[3 * v + 2] << '\n';
  for (int f = 0; f < m.num_faces(); ++f)
    out << "f " << m.F[3 * f] + 1 << ' ' << m.F[3 * f + 1] + 1 << ' ' << m.F[3 * f + 2] + 1 << '\n';
}

}  // namespace gauss
