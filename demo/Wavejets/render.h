// Headless renderer of the `wavejets` tool: orthographic view, one fixed light, z-buffer; meshes as
// triangles with smooth (per-vertex normal) shading, point sets as elliptical splats on their
// tangent planes; PNG output through libpng. No CGAL here (plain arrays in and out).
#ifndef WAVEJETS_DEMO_RENDER_H
#define WAVEJETS_DEMO_RENDER_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace wavejets_demo {

typedef std::array<double, 3> Vec3;
/// Faces of a mesh (a polygon soup): vertex indices per face, any number of vertices per face.
typedef std::vector<std::vector<std::size_t> > Faces;

/// A point set or a mesh to draw: positions, normals (any orientation; shading is two-sided), an
/// optional scalar per point (colored with a diverging map symmetric around 0), and faces: when
/// there are faces, they are drawn (polygons as triangle fans) and the points are not.
struct Cloud
{
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
  std::vector<double> scalar;   // empty: uniform material color
  double spacing = 0.;          // average point spacing (world units), sets the splat size
  Faces faces;                  // empty: a point set, drawn as splats
};

/// Area-weighted vertex normals of a polygon soup (the Newell normal of each face, whose length is
/// twice its area, summed at its vertices), unit length; zero where a vertex has no face of non-zero area.
/// Faces refer to vertices by index (< points.size()).
std::vector<Vec3> vertex_normals(const std::vector<Vec3>& points, const Faces& faces);

struct View_options
{
  int width = 800, height = 800;  // size of the whole image (all panels)
  Vec3 view = {{0., 0., 1.}};     // direction from the object toward the camera
  Vec3 up = {{0., 1., 0.}};       // world direction shown upward (projected)
  double splat = 1.0;             // splat radius, in average spacings (point sets)
};

struct Image
{
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;   // row-major, 3 bytes per pixel
};

/// Background color of every image (the tests check that some pixel differs from it).
const std::array<std::uint8_t, 3> background = {{255, 255, 255}};

/// Draws the clouds side by side, each in a panel of width/n x height pixels, all with one camera
/// framed on the bounding box of all clouds (so that the panels compare). Throws std::invalid_argument.
Image render(const std::vector<const Cloud*>& clouds, const View_options& options);

/// Writes an 8-bit RGB PNG with libpng; throws std::runtime_error with the reason.
void write_png(const Image& image, const std::string& path);

/// Reads a PNG (any color type) back as 8-bit RGB; throws std::runtime_error with the reason.
Image read_png(const std::string& path);

/// Writes a file atomically: the content goes to a temporary file in the same folder, renamed over
/// `path` by commit(); the temporary is removed if commit() is not reached, and on SIGINT/SIGTERM
/// in a program that called remove_output_files_on_interrupt().
class Output_file
{
public:
  explicit Output_file(const std::string& path);   // throws std::runtime_error
  ~Output_file();
  Output_file(const Output_file&) = delete;
  Output_file& operator=(const Output_file&) = delete;
  const std::string& temporary_path() const { return tmp_; }
  void commit();                                    // throws std::runtime_error
private:
  std::string path_, tmp_;
  bool committed_ = false;
};

/// For programs (the tool): SIGINT and SIGTERM remove the temporary file of the Output_file being
/// written, print that nothing was written and exit. A library (the Python module) never calls it,
/// so that the host keeps its own handlers (Python's KeyboardInterrupt).
void remove_output_files_on_interrupt();

} // namespace wavejets_demo

#endif // WAVEJETS_DEMO_RENDER_H
