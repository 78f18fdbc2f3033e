// The four point-set functions on the vertices of a mesh (CGAL::Surface_mesh and
// CGAL::Polyhedron_3), through the mesh's vertex range and its vertex point map:
//   auto vs = vertices(mesh);
//   wavejet_enhance_positions<Tag>(vs, k, gain, order(4).point_map(mesh.points()));
// Checks that the results are bitwise those of the same points in a std::vector (same order),
// that the faces are untouched, that vertex normals from PMP::compute_vertex_normals serve as
// input normals, that Sequential_tag and Parallel_tag agree, and that removed vertices of a
// Surface_mesh (not yet garbage-collected) are neither read nor written.
// Usage: test_meshes [mesh.off]   (default: data/fandisk.off)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/OFF.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/property_map.h>
#include <CGAL/wavejet_enhance_normals.h>
#include <CGAL/wavejet_enhance_positions.h>
#include <CGAL/wavejet_estimate_curvatures.h>
#include <CGAL/wavejet_estimate_normals.h>

#include <boost/property_map/property_map.hpp>

#include <cassert>
#include <cstdlib>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "wavejets_test_support.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index Vertex;
typedef CGAL::Polyhedron_3<K> Polyhedron;
typedef std::pair<Point, Vector> Pwn;
namespace WP = CGAL::Wavejets::parameters;
namespace PMP = CGAL::Polygon_mesh_processing;

using wavejets_test::Case;

static const unsigned int k = 24;

// The faces of a mesh as vertex indices, in face order.
static std::vector<std::vector<std::size_t> > faces_of(const Mesh& m)
{
  std::vector<std::vector<std::size_t> > f;
  for(Mesh::Face_index fi : m.faces()) {
    f.emplace_back();
    for(Vertex v : CGAL::vertices_around_face(m.halfedge(fi), m)) f.back().push_back(std::size_t(v));
  }
  return f;
}

static std::vector<Pwn> copy_with_normals(const Mesh& m, const Mesh::Property_map<Vertex, Vector>& normals)
{
  std::vector<Pwn> v;
  for(Vertex vi : m.vertices()) v.emplace_back(m.point(vi), normals[vi]);
  return v;
}

template <class Tag>
static void check_surface_mesh(const Mesh& original)
{
  const auto pm = CGAL::First_of_pair_property_map<Pwn>();
  const auto nm = CGAL::Second_of_pair_property_map<Pwn>();

  // Input normals from the mesh's faces, as a user would compute them.
  Mesh mesh = original;
  Mesh::Property_map<Vertex, Vector> vnormals = mesh.add_property_map<Vertex, Vector>("v:normal", CGAL::NULL_VECTOR).first;
  PMP::compute_vertex_normals(mesh, vnormals);
  const std::vector<Pwn> reference_input = copy_with_normals(mesh, vnormals);
  const std::vector<std::vector<std::size_t> > faces_before = faces_of(mesh);

  // 1. Positions, moved along the Wavejet normals; Wavejet normals written to the mesh's map.
  {
    Mesh m = mesh;
    Mesh::Property_map<Vertex, Vector> n = m.add_property_map<Vertex, Vector>("v:normal").first;
    Mesh::Property_map<Vertex, bool> fitted = m.add_property_map<Vertex, bool>("v:fitted", false).first;
    auto vs = vertices(m);
    const CGAL::Wavejets::Processing_report r = CGAL::wavejet_enhance_positions<Tag>(
      vs, k, 2.0, WP::order(4).write_normals(true).fitted_map(fitted).point_map(m.points()).normal_map(n));
    std::vector<Pwn> v = reference_input;
    const CGAL::Wavejets::Processing_report rv = CGAL::wavejet_enhance_positions<Tag>(
      v, k, 2.0, WP::order(4).write_normals(true).point_map(pm).normal_map(nm));
    CHECK(r.number_of_points == m.number_of_vertices(), "enhance_positions: every vertex is processed");
    CHECK(r.number_of_fitted_points == rv.number_of_fitted_points && r.number_of_clamped_points == rv.number_of_clamped_points,
          "enhance_positions: same report as on a vector");
    CHECK(r.number_of_fitted_points > 0.99 * double(m.number_of_vertices()), "enhance_positions: most vertices fitted");
    std::size_t i = 0, same = 0, moved = 0, fitted_count = 0;
    for(Vertex vi : m.vertices()) {
      same += (m.point(vi) == v[i].first && n[vi] == v[i].second);
      moved += (m.point(vi) != reference_input[i].first);
      fitted_count += fitted[vi];
      ++i;
    }
    CHECK(same == m.number_of_vertices(), "enhance_positions: mesh and vector results differ at " << (m.number_of_vertices() - same) << " vertices");
    CHECK(moved > m.number_of_vertices() / 2, "enhance_positions: the vertices did not move (" << moved << ")");
    CHECK(fitted_count == r.number_of_fitted_points, "enhance_positions: fitted_map on the mesh");
    CHECK(faces_of(m) == faces_before, "enhance_positions: faces changed");
    CHECK(m.number_of_vertices() == mesh.number_of_vertices() && m.number_of_faces() == mesh.number_of_faces(),
          "enhance_positions: element counts changed");
    CHECK(m.is_valid(false), "enhance_positions: the mesh is no longer valid");
  }
  // 2. Without normals at all (only the point map): same positions as a vector of points.
  {
    Mesh m = original;
    auto vs = vertices(m);
    CGAL::wavejet_enhance_positions<Tag>(vs, k, 0.0, WP::order(3).point_map(m.points()));
    std::vector<Point> v;
    for(Vertex vi : original.vertices()) v.push_back(original.point(vi));
    CGAL::wavejet_enhance_positions<Tag>(v, k, 0.0, WP::order(3));
    std::size_t i = 0, same = 0;
    for(Vertex vi : m.vertices()) same += (m.point(vi) == v[i++]);
    CHECK(same == m.number_of_vertices(), "enhance_positions without normals: mesh and vector differ");
    CHECK(faces_of(m) == faces_of(original), "enhance_positions without normals: faces changed");
  }
  // 3. Normals, oriented like the vertex normals.
  {
    Mesh m = mesh;
    Mesh::Property_map<Vertex, Vector> n = m.add_property_map<Vertex, Vector>("v:normal").first;
    auto vs = vertices(m);
    CGAL::wavejet_estimate_normals<Tag>(vs, k, WP::order(2).orient_with_input_normals(true).point_map(m.points()).normal_map(n));
    std::vector<Pwn> v = reference_input;
    CGAL::wavejet_estimate_normals<Tag>(v, k, WP::order(2).orient_with_input_normals(true).point_map(pm).normal_map(nm));
    std::size_t i = 0, same = 0, agree = 0;
    for(Vertex vi : m.vertices()) {
      same += (n[vi] == v[i].second && m.point(vi) == reference_input[i].first);
      agree += (n[vi] * reference_input[i].second > 0);
      ++i;
    }
    CHECK(same == m.number_of_vertices(), "estimate_normals: mesh and vector differ");
    CHECK(agree > 0.99 * double(m.number_of_vertices()), "estimate_normals: not oriented like the vertex normals (" << agree << ")");
  }
  // 4. Curvatures into mesh property maps.
  {
    Mesh m = mesh;
    Mesh::Property_map<Vertex, Vector> n = m.add_property_map<Vertex, Vector>("v:normal").first;
    Mesh::Property_map<Vertex, double> H = m.add_property_map<Vertex, double>("v:H", 0.).first;
    Mesh::Property_map<Vertex, double> G = m.add_property_map<Vertex, double>("v:K", 0.).first;
    auto vs = vertices(m);
    CGAL::wavejet_estimate_curvatures<Tag>(vs, k, WP::order(2).mean_curvature_map(H).gaussian_curvature_map(G)
                                                  .point_map(m.points()).normal_map(n));
    // Reference: a range of indices, with the maps as vectors indexed by them.
    std::vector<std::size_t> indices;
    std::vector<Point> pv;
    std::vector<Vector> nv;
    for(const Pwn& p : reference_input) { indices.push_back(pv.size()); pv.push_back(p.first); nv.push_back(p.second); }
    std::vector<double> Hv(pv.size(), 0.), Gv(pv.size(), 0.);
    CGAL::wavejet_estimate_curvatures<Tag>(indices, k, WP::order(2).mean_curvature_map(CGAL::make_property_map(Hv))
                                                       .gaussian_curvature_map(CGAL::make_property_map(Gv))
                                                       .point_map(CGAL::make_property_map(pv))
                                                       .normal_map(CGAL::make_property_map(nv)));
    std::size_t i = 0, same = 0, nonzero = 0;
    for(Vertex vi : m.vertices()) {
      same += (H[vi] == Hv[i] && G[vi] == Gv[i]);
      nonzero += (H[vi] != 0.);
      ++i;
    }
    CHECK(same == m.number_of_vertices(), "estimate_curvatures: mesh and vector differ");
    CHECK(nonzero > m.number_of_vertices() / 2, "estimate_curvatures: no curvature written");
  }
  // 5. Normal filter with a complex gain (twist).
  {
    Mesh m = mesh;
    Mesh::Property_map<Vertex, Vector> n = m.add_property_map<Vertex, Vector>("v:normal").first;
    auto vs = vertices(m);
    CGAL::wavejet_enhance_normals<Tag>(vs, k, std::complex<double>(1., 1.), WP::order(4).point_map(m.points()).normal_map(n));
    std::vector<Pwn> v = reference_input;
    CGAL::wavejet_enhance_normals<Tag>(v, k, std::complex<double>(1., 1.), WP::order(4).point_map(pm).normal_map(nm));
    std::size_t i = 0, same = 0, changed = 0;
    for(Vertex vi : m.vertices()) {
      same += (n[vi] == v[i].second && m.point(vi) == reference_input[i].first);
      changed += (n[vi] != reference_input[i].second);
      ++i;
    }
    CHECK(same == m.number_of_vertices(), "enhance_normals: mesh and vector differ");
    CHECK(changed > m.number_of_vertices() / 2, "enhance_normals: the normals did not change");
  }
}

// Removed vertices of a Surface_mesh are skipped by vertices(mesh): they are neither read (as
// neighbors) nor written. Remove the faces around one vertex, then the vertex itself.
static void check_removed_vertices(const Mesh& original)
{
  Mesh m = original;
  const Vertex gone = *m.vertices().begin();
  const Point gone_point = m.point(gone);
  std::vector<Mesh::Face_index> around;
  for(Mesh::Face_index f : CGAL::faces_around_target(m.halfedge(gone), m))
    if(f != Mesh::null_face()) around.push_back(f);
  for(Mesh::Face_index f : around) CGAL::Euler::remove_face(m.halfedge(f), m);
  if(!m.is_removed(gone)) m.remove_vertex(gone);
  CHECK(m.has_garbage() && m.is_removed(gone), "setup: the vertex is not removed");
  std::vector<Point> v;
  for(Vertex vi : m.vertices()) v.push_back(m.point(vi));
  auto vs = vertices(m);
  CGAL::wavejet_enhance_positions<CGAL::Sequential_tag>(vs, k, 2.0, WP::order(4).point_map(m.points()));
  CGAL::wavejet_enhance_positions<CGAL::Sequential_tag>(v, k, 2.0, WP::order(4));
  std::size_t i = 0, same = 0;
  for(Vertex vi : m.vertices()) same += (m.point(vi) == v[i++]);
  CHECK(i == v.size() && same == v.size(), "removed vertices: results differ from the vector of the remaining points");
  CHECK(m.point(gone) == gone_point, "removed vertices: a removed vertex was written");
}

// Polyhedron_3: its vertex range (Vertex_handle keys) and vertex_point map; results are those of
// the Surface_mesh read from the same file (same vertex order).
static void check_polyhedron(const std::string& path, const Mesh& mesh)
{
  Polyhedron P;
  CHECK(CGAL::IO::read_OFF(path, P), "cannot read " << path << " as a Polyhedron_3");
  CHECK(P.size_of_vertices() == mesh.number_of_vertices(), "Polyhedron_3: vertex count");
  std::vector<std::vector<Point> > facets_before;
  for(auto f = P.facets_begin(); f != P.facets_end(); ++f) {
    facets_before.emplace_back();
    auto h = f->facet_begin();
    do { facets_before.back().push_back(h->vertex()->point()); } while(++h != f->facet_begin());
  }
  typedef boost::graph_traits<Polyhedron>::vertex_descriptor Pv;
  std::map<Pv, Vector> normal_storage;
  boost::associative_property_map<std::map<Pv, Vector> > normals(normal_storage);
  PMP::compute_vertex_normals(P, normals);
  auto vs = vertices(P);
  const CGAL::Wavejets::Processing_report r = CGAL::wavejet_enhance_positions<CGAL::Sequential_tag>(
    vs, k, 2.0, WP::order(4).point_map(get(CGAL::vertex_point, P)).normal_map(normals));
  CHECK(r.number_of_points == P.size_of_vertices(), "Polyhedron_3: every vertex processed");

  Mesh m = mesh;
  Mesh::Property_map<Vertex, Vector> n = m.add_property_map<Vertex, Vector>("v:normal", CGAL::NULL_VECTOR).first;
  PMP::compute_vertex_normals(m, n);
  auto ms = vertices(m);
  CGAL::wavejet_enhance_positions<CGAL::Sequential_tag>(
    ms, k, 2.0, WP::order(4).point_map(m.points()).normal_map(n));
  std::size_t same = 0, moved = 0;
  auto pv = P.vertices_begin();
  for(Vertex vi : m.vertices()) {
    same += (pv->point() == m.point(vi));
    moved += (pv->point() != mesh.point(vi));
    ++pv;
  }
  CHECK(same == m.number_of_vertices(), "Polyhedron_3 and Surface_mesh results differ at " << (m.number_of_vertices() - same) << " vertices");
  CHECK(moved > m.number_of_vertices() / 2, "Polyhedron_3: the vertices did not move");
  // The facets still join the same vertices (now at their moved positions): compare the
  // combinatorics through the vertex order.
  std::map<const void*, std::size_t> index;
  std::size_t i = 0;
  for(auto v = P.vertices_begin(); v != P.vertices_end(); ++v) index[&*v] = i++;
  std::vector<std::vector<std::size_t> > facets;
  for(auto f = P.facets_begin(); f != P.facets_end(); ++f) {
    facets.emplace_back();
    auto h = f->facet_begin();
    do { facets.back().push_back(index[&*h->vertex()]); } while(++h != f->facet_begin());
  }
  CHECK(facets == faces_of(mesh), "Polyhedron_3: facets changed");
  CHECK(P.is_valid(), "Polyhedron_3: no longer valid");
}

// Sequential and parallel runs on the mesh: bitwise identical. (Only this function under
// Parallel_tag: the others share its driver, and each instantiation costs compile memory.)
static void check_sequential_equals_parallel(const Mesh& mesh)
{
  Mesh a = mesh, b = mesh;
  auto va = vertices(a);
  auto vb = vertices(b);
  CGAL::wavejet_enhance_positions<CGAL::Sequential_tag>(va, k, 3.0, WP::order(4).point_map(a.points()));
  CGAL::wavejet_enhance_positions<CGAL::Parallel_if_available_tag>(vb, k, 3.0, WP::order(4).point_map(b.points()));
  std::size_t same = 0;
  for(Vertex vi : a.vertices()) same += (a.point(vi) == b.point(vi));
  CHECK(same == a.number_of_vertices(), "Sequential_tag and Parallel_tag differ on a mesh");
}

static const std::string fandisk_path = "data/fandisk.off";

/// data/fandisk.off, read once.
static const Mesh& fandisk()
{
  static const Mesh mesh = [] {
    Mesh m;
    if(!CGAL::IO::read_OFF(fandisk_path, m) || m.number_of_faces() == 0)
      throw std::runtime_error("cannot read the mesh " + fandisk_path);
    std::cout << fandisk_path << ": " << m.number_of_vertices() << " vertices, " << m.number_of_faces() << " faces"
              << std::endl;
    return m;
  }();
  return mesh;
}

int main(int argc, char** argv)
{
  return wavejets_test::run_cases(argc, argv, {
    Case{"surface_mesh.same_as_vector", [] { check_surface_mesh<CGAL::Sequential_tag>(fandisk()); }},
    Case{"surface_mesh.sequential_equals_parallel", [] { check_sequential_equals_parallel(fandisk()); }},
    Case{"surface_mesh.removed_vertices", [] { check_removed_vertices(fandisk()); }},
    Case{"polyhedron.same_as_surface_mesh", [] { check_polyhedron(fandisk_path, fandisk()); }},
  });
}
