// Reading and writing the point sets and meshes of the `wavejets` tool and of the Python module
// through CGAL's IO: PLY, OFF, OBJ, XYZ and PWN in; PLY (every property, a mesh's faces), OFF and OBJ out.
#include "point_set_io.h"
#include "platform.h"

#include <CGAL/Point_set_3/IO.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>

namespace wavejets_demo {

namespace {

// The faces of an OFF or PLY mesh, read again as a polygon soup (the point set reader skips them).
// The soup's vertices must be the point set's, one for one.
bool read_faces(const std::string& path, const std::string& ext, Input& in)
{
  std::ifstream is(path, std::ios::binary);
  std::vector<Point> soup_points;
  Faces faces;
  const bool ok = ext == "off" ? CGAL::IO::read_OFF(is, soup_points, faces) : CGAL::IO::read_PLY(is, soup_points, faces);
  if(!ok) return false;
  if(soup_points.size() != in.points.size())
    throw std::runtime_error(std::to_string(in.points.size()) + " vertices read, but the faces refer to " +
                             std::to_string(soup_points.size()));
  in.faces.swap(faces);
  return true;
}

// An OBJ file: vertices (v) and faces (f) as a polygon soup; no vertex normals (OBJ's are per corner).
bool read_obj(std::istream& is, Input& in)
{
  std::vector<Point> soup_points;
  Faces faces;
  if(!CGAL::IO::read_OBJ(is, soup_points, faces)) return false;
  for(const Point& p : soup_points) in.points.insert(p);
  in.faces.swap(faces);
  return true;
}


// Appends a face element (list uchar|uint int vertex_indices) to a PLY written by CGAL for the vertices:
// its header gets the element before end_header, its body the faces after the vertices.
void append_ply_faces(std::string& ply, const Faces& faces, bool ascii)
{
  std::size_t largest = 0;
  for(const std::vector<std::size_t>& f : faces) largest = std::max(largest, f.size());
  const bool wide = largest > 255;
  const std::size_t end = ply.find("end_header\n");
  if(end == std::string::npos) throw File_error("internal error: no end_header in the PLY written by CGAL");
  ply.insert(end, "element face " + std::to_string(faces.size()) + "\nproperty list " + (wide ? "uint" : "uchar") +
                    " int vertex_indices\n");
  std::ostringstream body;
  if(ascii)
    for(const std::vector<std::size_t>& f : faces) {
      body << f.size();
      for(std::size_t v : f) body << " " << v;
      body << "\n";
    }
  else
    for(const std::vector<std::size_t>& f : faces) {
      // PLY binary_little_endian; the tool only builds on little-endian machines (x86, ARM).
      if(wide) { const std::uint32_t n = std::uint32_t(f.size()); body.write(reinterpret_cast<const char*>(&n), 4); }
      else { const unsigned char n = (unsigned char)(f.size()); body.write(reinterpret_cast<const char*>(&n), 1); }
      for(std::size_t v : f) { const std::int32_t i = std::int32_t(v); body.write(reinterpret_cast<const char*>(&i), 4); }
    }
  ply += body.str();
}

void write_off_or_obj(std::ostream& os, const Point_set& points, const Faces& faces, Output_format format)
{
  os.precision(17);
  const bool normals = points.has_normal_map();
  if(format == Output_format::OFF)
    os << (normals ? "NOFF\n" : "OFF\n") << points.size() << " " << faces.size() << " 0\n";
  for(Point_set::Index i : points) {
    const Point& p = points.point(i);
    os << (format == Output_format::OBJ ? "v " : "") << p.x() << " " << p.y() << " " << p.z();
    if(normals) {
      const Vector& n = points.normal(i);
      os << (format == Output_format::OBJ ? "\nvn " : " ") << n.x() << " " << n.y() << " " << n.z();
    }
    os << "\n";
  }
  for(const std::vector<std::size_t>& f : faces) {
    if(format == Output_format::OFF) os << f.size();
    else os << "f";
    for(std::size_t v : f) {
      if(format == Output_format::OFF) os << " " << v;
      else if(normals) os << " " << v + 1 << "//" << v + 1;
      else os << " " << v + 1;
    }
    os << "\n";
  }
}

} // namespace

bool call_cgal_io(const std::function<bool()>& read_or_write, std::string& why)
{
  static std::mutex one_at_a_time;
  const std::lock_guard<std::mutex> lock(one_at_a_time);
  std::ostringstream messages;
  std::streambuf* saved = std::cerr.rdbuf(messages.rdbuf());
  bool ok = false;
  try {
    ok = read_or_write();
  } catch(const std::exception& e) {
    messages << e.what() << "\n";
  }
  std::cerr.rdbuf(saved);
  if(!ok) {
    why = messages.str();
    why = why.substr(0, why.find('\n'));
    if(why.compare(0, 7, "Error: ") == 0) why = why.substr(7);
  }
  return ok;
}

std::string lower_extension(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for(char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

const Ply_header::Element* Ply_header::element(const std::string& name) const
{
  for(auto e = elements.rbegin(); e != elements.rend(); ++e)
    if(e->name == name) return &*e;
  return nullptr;
}

Ply_header read_ply_header(std::istream& is)
{
  Ply_header h;
  std::string line;
  for(int i = 0; i < 100000 && std::getline(is, line); ++i) {
    h.lines.push_back(line + "\n");
    if(!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream s(line);
    std::string word, a, b;
    s >> word >> a >> b;
    if(word == "format") h.format = a;
    else if(word == "element") {
      Ply_header::Element e;
      e.name = a;
      e.count = std::strtoull(b.c_str(), nullptr, 10);
      e.line = h.lines.size() - 1;
      h.elements.push_back(e);
    } else if(word == "property" && !h.elements.empty()) {
      std::string index_type, name;
      if(a == "list") s >> index_type >> name;   // property list COUNT_TYPE INDEX_TYPE NAME
      h.elements.back().properties.push_back(a == "list" ? Ply_header::Property{"list", name} : Ply_header::Property{a, b});
    } else if(word == "end_header") {
      h.complete = true;
      break;
    }
  }
  return h;
}

void check_ply_coordinate_types(const Ply_header& header, const std::string& path)
{
  std::string types[6];
  const char* names[6] = {"x", "y", "z", "nx", "ny", "nz"};
  if(const Ply_header::Element* vertex = header.element("vertex"))
    for(const Ply_header::Property& p : vertex->properties)
      for(int f = 0; f < 6; ++f)
        if(p.name == names[f]) types[f] = p.type;
  auto is_float = [](const std::string& t) { return t == "float" || t == "float32"; };
  auto is_double = [](const std::string& t) { return t == "double" || t == "float64"; };
  const bool normals = !types[3].empty() && !types[4].empty() && !types[5].empty();   // else CGAL skips them
  const bool floats = is_float(types[0]) || is_float(types[1]) || is_float(types[2]);
  for(int f = 0; f < (normals ? 6 : 3); ++f)
    if(!types[f].empty() && !(is_float(types[f]) || (!floats && is_double(types[f]))))
      throw File_error(path + ": PLY property '" + types[f] + " " + names[f] + "' cannot be read: x, y, z, nx, ny, nz must be "
                       "float or double, and all float when a coordinate is float (convert the file, e.g. in MeshLab or CloudCompare)");
}

Input read_input(const std::string& path)
{
  const auto t0 = std::chrono::steady_clock::now();
  Input in;
  const std::string ext = lower_extension(path);
  if(ext != "ply" && ext != "xyz" && ext != "pwn" && ext != "off" && ext != "obj")
    throw File_error(path + ": unsupported format '." + ext + "' (expected .ply, .xyz, .pwn, .off or .obj)");
  in.format = ext == "pwn" ? "XYZ" : ext == "off" ? "OFF" : ext == "ply" ? "PLY" : ext == "obj" ? "OBJ" : "XYZ";
  std::ifstream is(path, std::ios::binary);
  if(!is) throw File_error(path + ": cannot open (" + std::strerror(errno) + ")");
  if(is.peek() == std::ifstream::traits_type::eof()) throw File_error(path + ": the file is empty");

  Ply_header header;
  if(ext == "ply") {
    header = read_ply_header(is);
    check_ply_coordinate_types(header, path);
    is.clear();
    is.seekg(0);
  }
  std::string why;
  const bool ok = call_cgal_io([&] {
    bool read = false;
    if(ext == "ply") read = CGAL::IO::read_PLY(is, in.points);
    else if(ext == "off") read = CGAL::IO::read_OFF(is, in.points);
    else if(ext == "obj") read = read_obj(is, in);
    else read = CGAL::IO::read_XYZ(is, in.points);
    const Ply_header::Element* faces = header.element("face");
    if(read && (ext == "off" || (faces && faces->count > 0))) read = read_faces(path, ext, in);
    return read;
  }, why);
  if(!ok) throw File_error(path + ": not a valid " + in.format + " file (" + (why.empty() ? "malformed or truncated" : why) + ")");
  if(const Ply_header::Element* vertices = header.element("vertex"))
    if(vertices->count != in.points.size())
      throw File_error(path + ": truncated PLY (the header announces " + std::to_string(vertices->count) +
                       " vertices, " + std::to_string(in.points.size()) + " could be read)");
  if(in.points.empty()) throw File_error(path + ": contains no points");
  for(std::size_t f = 0; f < in.faces.size(); ++f)
    for(std::size_t v : in.faces[f])
      if(v >= in.points.size())
        throw File_error(path + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + " but there are " +
                         std::to_string(in.points.size()) + " vertices");

  std::size_t index = 0;
  for(Point_set::Index i : in.points) {
    const Point& p = in.points.point(i);
    if(!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      throw File_error(path + ": point " + std::to_string(index) +
                       " has a NaN or infinite coordinate (remove such points first)");
    ++index;
  }
  // A single point, or points that all coincide, have no surface: no neighborhood radius, no
  // fit, no shading. Say so here, for every command, rather than fail later without the file name.
  const Point& first = in.points.point(*in.points.begin());
  bool all_same = true;
  for(Point_set::Index i : in.points)
    if(in.points.point(i) != first) { all_same = false; break; }
  if(all_same)
    throw File_error(path + (in.points.size() == 1 ? std::string(": contains a single point")
                                                   : ": all " + std::to_string(in.points.size()) + " points coincide") +
                     " (no surface to fit)");
  // Normals count as present when at least one is finite and non-zero.
  if(in.points.has_normal_map()) {
    bool any = false;
    for(Point_set::Index i : in.points) {
      const Vector& n = in.points.normal(i);
      if(std::isfinite(n.squared_length()) && n.squared_length() > 0) { any = true; break; }
    }
    if(!any) in.points.remove_normal_map();
  }
  in.had_normals = in.points.has_normal_map();
  in.read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return in;
}

Output_format output_format(const std::string& path)
{
  const std::string e = lower_extension(path);
  return e == "off" ? Output_format::OFF : e == "obj" ? Output_format::OBJ : Output_format::PLY;
}

std::string ply_text(const Point_set& points, bool ascii, const std::string& comment)
{
  std::ostringstream ply;
  if(ascii) { CGAL::IO::set_ascii_mode(ply); ply.precision(17); }
  else CGAL::IO::set_binary_mode(ply);
  std::string why;
  if(!call_cgal_io([&] { return CGAL::IO::write_PLY(ply, points, comment); }, why))
    throw File_error("CGAL could not write a PLY (" + why + ")");
  return ply.str();
}

void write_output(const Point_set& points, const Faces& faces, const std::string& path, bool ascii,
                  const std::string& comment)
{
  Output_file out(path);
  {
    std::ofstream os(out.temporary_path(), std::ios::binary);
    if(!os) throw File_error(path + ": cannot write (" + std::strerror(errno) + ")");
    const Output_format format = output_format(path);
    bool ok = true;
    if(format == Output_format::PLY) {
      std::string text;
      try {
        text = ply_text(points, ascii, comment);
      } catch(const File_error&) { ok = false; }
      if(ok && !faces.empty()) append_ply_faces(text, faces, ascii);
      os.write(text.data(), std::streamsize(text.size()));
    } else
      write_off_or_obj(os, points, faces, format);
    os.close();
    if(!ok || !os) throw File_error(path + ": cannot write (disk full or not writable?)");
  }
  out.commit();
}

} // namespace wavejets_demo
