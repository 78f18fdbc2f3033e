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
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

namespace wavejets_demo {

namespace {

// Number of elements `name` (vertex, face) announced by a PLY header; -1 if not found.
long ply_header_count(const std::string& path, const std::string& name)
{
  std::ifstream is(path, std::ios::binary);
  std::string line;
  long n = -1;
  for(int i = 0; i < 1000 && std::getline(is, line); ++i) {
    std::istringstream s(line);
    std::string a, b;
    long c;
    if(s >> a >> b >> c && a == "element" && b == name) n = c;
    if(line.compare(0, 10, "end_header") == 0) break;
  }
  return n;
}

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

std::string lower_extension(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for(char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

void check_ply_coordinate_types(const std::string& path)
{
  std::ifstream is(path, std::ios::binary);
  std::string line, element, types[6];
  const char* names[6] = {"x", "y", "z", "nx", "ny", "nz"};
  for(int i = 0; i < 100000 && std::getline(is, line) && line.compare(0, 10, "end_header") != 0; ++i) {
    std::istringstream s(line);
    std::string word, a, b;
    s >> word >> a >> b;
    if(word == "element") element = a;
    if(word == "property" && element == "vertex")
      for(int f = 0; f < 6; ++f)
        if(b == names[f]) types[f] = a;
  }
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

  if(ext == "ply") check_ply_coordinate_types(path);
  // CGAL reports its parse errors on std::cerr: capture them, to give one line.
  std::ostringstream cgal_messages;
  std::streambuf* saved = std::cerr.rdbuf(cgal_messages.rdbuf());
  bool ok = false;
  try {
    if(ext == "ply") ok = CGAL::IO::read_PLY(is, in.points);
    else if(ext == "off") ok = CGAL::IO::read_OFF(is, in.points);
    else if(ext == "obj") ok = read_obj(is, in);
    else ok = CGAL::IO::read_XYZ(is, in.points);
    if(ok && (ext == "off" || (ext == "ply" && ply_header_count(path, "face") > 0))) ok = read_faces(path, ext, in);
  } catch(const std::exception& e) {
    cgal_messages << e.what() << "\n";
    ok = false;
  }
  std::cerr.rdbuf(saved);
  if(!ok) {
    std::string why = cgal_messages.str();
    why = why.substr(0, why.find('\n'));
    if(why.compare(0, 7, "Error: ") == 0) why = why.substr(7);
    if(why.empty()) why = "malformed or truncated";
    throw File_error(path + ": not a valid " + in.format + " file (" + why + ")");
  }
  if(ext == "ply") {
    const long announced = ply_header_count(path, "vertex");
    if(announced >= 0 && std::size_t(announced) != in.points.size())
      throw File_error(path + ": truncated PLY (the header announces " + std::to_string(announced) +
                       " vertices, " + std::to_string(in.points.size()) + " could be read)");
  }
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
  std::ostringstream cgal_messages;
  std::streambuf* saved = std::cerr.rdbuf(cgal_messages.rdbuf());
  const bool ok = CGAL::IO::write_PLY(ply, points, comment);
  std::cerr.rdbuf(saved);
  if(!ok) throw File_error("CGAL could not write a PLY (" + cgal_messages.str().substr(0, cgal_messages.str().find('\n')) + ")");
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
