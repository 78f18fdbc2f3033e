// Reading and writing the point sets and meshes of the `wavejets` tool and of the Python module
// through CGAL's IO: PLY, OFF, OBJ, XYZ and PWN in; PLY (every property, a mesh's faces), OFF and OBJ out.
#ifndef WAVEJETS_DEMO_POINT_SET_IO_H
#define WAVEJETS_DEMO_POINT_SET_IO_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Point_set_3.h>

#include "render.h"   // Faces

#include <cstdint>
#include <functional>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace wavejets_demo {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef CGAL::Point_set_3<Point, Vector> Point_set;

/// A file that cannot be read or written; its message names the file and says why, on one line.
struct File_error : std::runtime_error { using std::runtime_error::runtime_error; };

/// Calls `read_or_write` (a CGAL reader or writer: whether it succeeded) with what CGAL prints on
/// std::cerr captured, as well as the message of an exception it throws. Returns false on failure,
/// with the first line of the messages (without "Error: ") in `why`. One call at a time in the
/// process (std::cerr is the process's): threads may read and write concurrently.
bool call_cgal_io(const std::function<bool()>& read_or_write, std::string& why);

/// The extension of `path`, lower case, without the dot ("" if none).
std::string lower_extension(const std::string& path);

/// The header of a PLY file: its format, its elements and their properties, its lines.
struct Ply_header
{
  struct Property { std::string type, name; };   // type "list" for a list property
  struct Element
  {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    std::size_t line = 0;                         // the index of its line in `lines`
  };
  std::string format;                  // ascii, binary_little_endian or binary_big_endian
  std::vector<Element> elements;
  std::vector<std::string> lines;      // as in the file, each with its end of line
  bool complete = false;               // ends with end_header
  /// The last element named `name`, or null.
  const Element* element(const std::string& name) const;
};

/// Reads the header of a PLY file from `is` (up to 100,000 lines), leaving `is` at the first byte
/// of the body.
Ply_header read_ply_header(std::istream& is);

/// Throws `File_error` if `header` (of the file `path`) gives x, y, z, nx, ny or nz a type that
/// CGAL's point set reader cannot read (it dereferences a null pointer): they must be float or
/// double, and all float when x, y or z is float.
void check_ply_coordinate_types(const Ply_header& header, const std::string& path);

/// A point set or a mesh as read from a file.
struct Input
{
  Point_set points;
  bool had_normals = false;
  double read_seconds = 0.;
  std::string format;
  // Faces of a mesh input (OFF, PLY with a face element, OBJ), as vertex indices, copied as they
  // are (a polygon soup: non-manifold, badly oriented or non-triangular faces are kept). Empty: a point set.
  Faces faces;
  bool is_mesh() const { return !faces.empty(); }
};

/// Reads a point set (`.xyz`, `.pwn`, `.ply` or `.off` without faces) or a mesh (`.off`, `.obj`,
/// `.ply` with faces), its normals where the file has some (all zero or non-finite: none) and the
/// other PLY properties. Throws `File_error` for an unreadable, malformed, truncated or empty file,
/// a NaN or infinite coordinate, a face referring to a missing vertex, or points that all coincide.
Input read_input(const std::string& path);

/// Output formats: PLY (the point set's properties, and the faces of a mesh), or for a mesh OFF or
/// OBJ (positions, normals and faces only); chosen by the extension of the path (PLY otherwise).
enum class Output_format { PLY, OFF, OBJ };
Output_format output_format(const std::string& path);

/// The PLY file of `points` with every property, as CGAL writes it: binary little-endian (doubles)
/// unless `ascii` (17 significant digits). A vertex's bytes depend on that vertex only.
std::string ply_text(const Point_set& points, bool ascii, const std::string& comment);

/// Writes `points` (with every property, in PLY) and `faces` to `path`, through a temporary file
/// renamed at the end: on error, `path` is left untouched. PLY is binary little-endian (doubles)
/// unless `ascii` (17 significant digits). Throws `File_error`.
void write_output(const Point_set& points, const Faces& faces, const std::string& path, bool ascii,
                  const std::string& comment);

} // namespace wavejets_demo

#endif // WAVEJETS_DEMO_POINT_SET_IO_H
