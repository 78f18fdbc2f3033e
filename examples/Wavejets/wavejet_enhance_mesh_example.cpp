// Amplifies the surface details of a triangle mesh by moving its vertices (Wavejets position
// filter), then writes the mesh with its faces: the package's functions take the mesh's vertex
// range with the mesh's point map, and the vertex normals of the faces as input normals.
// Usage: wavejet_enhance_mesh_example [input.off] [output.off] [gain]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/wavejet_enhance_positions.h>

#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Vector_3 Vector;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index Vertex;
typedef CGAL::Parallel_if_available_tag Concurrency_tag;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : "data/anchor_dense.off";
  const char* dir = std::getenv("WAVEJETS_OUTPUT_DIR");
  const std::string output = argc > 2 ? argv[2] : std::string(dir ? dir : ".") + "/anchor_enhanced.off";
  const double gain = argc > 3 ? std::atof(argv[3]) : 2.;

  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh) || mesh.is_empty())
  {
    std::cerr << "Error: cannot read " << input << " as a polygon mesh" << std::endl;
    return EXIT_FAILURE;
  }

  // Input normals (they orient the Wavejet frames): the vertex normals of the faces.
  Mesh::Property_map<Vertex, Vector> normals = mesh.add_property_map<Vertex, Vector>("v:normal", CGAL::NULL_VECTOR).first;
  PMP::compute_vertex_normals(mesh, normals);

  // gain > 1 amplifies details, 0 <= gain < 1 flattens them, gain < 0 inverts them. The vertices
  // move along their Wavejet normals (each at most Rf/2); the faces are not touched.
  auto vs = vertices(mesh);
  const CGAL::Wavejets::Processing_report report = CGAL::wavejet_enhance_positions<Concurrency_tag>(
    vs, 30 /* neighbors */, gain,
    CGAL::Wavejets::parameters::order(3).point_map(mesh.points()).normal_map(normals));
  std::cout << mesh.number_of_vertices() << " vertices, " << mesh.number_of_faces() << " faces: " << report << std::endl;
  if(report.number_of_fitted_points == 0)
  {
    std::cerr << "Error: no vertex could be fitted" << std::endl;
    return EXIT_FAILURE;
  }

  // The normals of the result, from its faces (what a mesh viewer shows).
  PMP::compute_vertex_normals(mesh, normals);
  if(!CGAL::IO::write_polygon_mesh(output, mesh, CGAL::parameters::vertex_normal_map(normals).stream_precision(17)))
  {
    std::cerr << "Error: cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Wrote " << output << std::endl;
  return EXIT_SUCCESS;
}
