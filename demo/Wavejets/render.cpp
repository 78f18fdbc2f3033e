// Headless renderer (triangles and splats) and atomic output files of the `wavejets` tool (see render.h).
#include "render.h"
#include "platform.h"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace wavejets_demo {
namespace {

Vec3 operator-(const Vec3& a, const Vec3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
Vec3 operator+(const Vec3& a, const Vec3& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
Vec3 operator*(double s, const Vec3& a) { return {{s * a[0], s * a[1], s * a[2]}}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
bool finite(const Vec3& a) { return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]); }
Vec3 normalized(const Vec3& a)
{
  const double l = std::sqrt(dot(a, a));
  return l > 0 && std::isfinite(l) ? (1. / l) * a : Vec3{{0., 0., 0.}};
}

// Diverging blue - white - red map for t in [-1, 1].
Vec3 diverging(double t)
{
  const Vec3 white = {{0.92, 0.92, 0.90}}, blue = {{0.17, 0.33, 0.80}}, red = {{0.80, 0.10, 0.12}};
  t = std::max(-1., std::min(1., t));
  return t < 0 ? white + (-t) * (blue - white) : white + t * (red - white);
}

// Blinn-Phong shading of a unit normal facing the camera, with a base color.
struct Shader
{
  Vec3 light, half;
  Vec3 operator()(const Vec3& n, const Vec3& base) const
  {
    const double diffuse = std::max(0., dot(n, light));
    const double specular = 0.18 * std::pow(std::max(0., dot(n, half)), 40.);
    return (0.22 + 0.78 * diffuse) * base + Vec3{{specular, specular, specular}};
  }
};

const Vec3 material = {{0.78, 0.76, 0.70}};

} // namespace

std::vector<Vec3> vertex_normals(const std::vector<Vec3>& points, const Faces& faces)
{
  std::vector<Vec3> normals(points.size(), Vec3{{0., 0., 0.}});
  for(const std::vector<std::size_t>& f : faces) {
    Vec3 newell = {{0., 0., 0.}};   // twice the area vector of the (possibly non-planar) polygon
    for(std::size_t i = 0; i < f.size(); ++i) newell = newell + cross(points[f[i]], points[f[(i + 1) % f.size()]]);
    if(!finite(newell)) continue;
    for(std::size_t v : f) normals[v] = normals[v] + newell;
  }
  for(Vec3& n : normals) n = normalized(n);
  return normals;
}

Image render(const std::vector<const Cloud*>& clouds, const View_options& o)
{
  if(clouds.empty()) throw std::invalid_argument("nothing to render");
  if(o.width < 8 || o.height < 8 || o.width > 16384 || o.height > 16384)
    throw std::invalid_argument("image size must be between 8 and 16384 pixels");
  if(!(o.splat > 0) || !std::isfinite(o.splat)) throw std::invalid_argument("the splat size must be > 0");
  const Vec3 w = normalized(o.view);
  if(dot(w, w) == 0) throw std::invalid_argument("the view direction must be a non-zero vector");
  Vec3 right = normalized(cross(o.up, w));
  if(dot(right, right) < 0.5) right = normalized(cross(std::abs(w[2]) < 0.9 ? Vec3{{0, 0, 1}} : Vec3{{1, 0, 0}}, w));
  const Vec3 up = cross(w, right);
  const Vec3 light = normalized(w + 0.7 * up - 0.5 * right);   // from the upper left, in front
  const Shader shade{light, normalized(light + w)};

  const int n = int(clouds.size());
  const int ss = 2;                                               // supersampling per axis
  const int pw = o.width / n, W = pw * ss, H = o.height * ss;
  if(pw < 8) throw std::invalid_argument("image too narrow for the panels");

  for(const Cloud* c : clouds)
    for(const std::vector<std::size_t>& f : c->faces)
      for(std::size_t v : f)
        if(v >= c->points.size()) throw std::invalid_argument("a face refers to a vertex that does not exist");
  // One camera for all panels: the bounding box of all projected points.
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for(const Cloud* c : clouds)
    for(const Vec3& p : c->points)
      if(finite(p)) {
        const double x = dot(p, right), y = dot(p, up);
        x0 = std::min(x0, x); x1 = std::max(x1, x); y0 = std::min(y0, y); y1 = std::max(y1, y);
      }
  if(x0 > x1) throw std::invalid_argument("no finite point to render");
  const double extent = std::max(std::max(x1 - x0, y1 - y0), 1e-12);
  const double scale = 0.9 * std::min(W / std::max(x1 - x0, 1e-3 * extent), H / std::max(y1 - y0, 1e-3 * extent));
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);

  Image image;
  image.width = pw * n;
  image.height = o.height;
  image.rgb.assign(std::size_t(image.width) * image.height * 3, 0);
  std::vector<float> color(std::size_t(W) * H * 3), depth(std::size_t(W) * H);
  for(int panel = 0; panel < n; ++panel) {
    const Cloud& c = *clouds[panel];
    for(std::size_t i = 0; i < color.size(); i += 3)
      for(int k = 0; k < 3; ++k) color[i + k] = background[k] / 255.f;
    std::fill(depth.begin(), depth.end(), -std::numeric_limits<float>::infinity());
    double smax = 0.;   // scalar range: 95th percentile of |value|
    if(!c.scalar.empty()) {
      std::vector<double> a;
      for(double v : c.scalar) if(std::isfinite(v)) a.push_back(std::abs(v));
      if(!a.empty()) {
        std::nth_element(a.begin(), a.begin() + std::ptrdiff_t(0.95 * double(a.size() - 1)), a.end());
        smax = a[std::size_t(0.95 * double(a.size() - 1))];
      }
    }
    auto base_color = [&](double value) {
      return std::isfinite(value) ? diverging(smax > 0 ? value / smax : 0.) : Vec3{{0.5, 0.5, 0.5}};
    };
    // Screen position (x right, y down, in supersampled pixels) and depth (larger: nearer) of a point.
    auto project = [&](const Vec3& p) {
      return Vec3{{(dot(p, right) - cx) * scale + 0.5 * W, 0.5 * H - (dot(p, up) - cy) * scale, dot(p, w) * scale}};
    };
    auto put_pixel = [&](int x, int y, float z, const Vec3& rgb) {
      float& zb = depth[std::size_t(y) * W + x];
      if(z <= zb) return;
      zb = z;
      for(int k = 0; k < 3; ++k) color[(std::size_t(y) * W + x) * 3 + k] = float(std::min(1., rgb[k]));
    };
    const bool colored = c.scalar.size() == c.points.size();
    if(!c.faces.empty()) {
      // Mesh: each polygon as a fan of triangles, normals and scalars interpolated per pixel
      // (smooth shading), then normalized and turned toward the camera (two-sided).
      std::vector<Vec3> screen(c.points.size());
      for(std::size_t i = 0; i < c.points.size(); ++i) screen[i] = project(c.points[i]);
      auto normal_of = [&](std::size_t i) { return i < c.normals.size() ? c.normals[i] : Vec3{{0., 0., 0.}}; };
      for(const std::vector<std::size_t>& f : c.faces)
        for(std::size_t t = 1; t + 1 < f.size(); ++t) {
          const std::size_t v[3] = {f[0], f[t], f[t + 1]};
          if(!finite(c.points[v[0]]) || !finite(c.points[v[1]]) || !finite(c.points[v[2]])) continue;
          const Vec3 &a = screen[v[0]], &b = screen[v[1]], &d = screen[v[2]];
          const double area = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
          if(std::abs(area) < 1e-12) continue;   // seen edge-on: covers no pixel center
          // The face's own normal, for vertices without one.
          const Vec3 face_normal = normalized(cross(c.points[v[1]] - c.points[v[0]], c.points[v[2]] - c.points[v[0]]));
          Vec3 vn[3];
          for(int j = 0; j < 3; ++j) {
            vn[j] = normalized(normal_of(v[j]));
            if(dot(vn[j], vn[j]) == 0) vn[j] = face_normal;
          }
          const int xa = std::max(0, int(std::floor(std::min({a[0], b[0], d[0]})))),
                    xb = std::min(W - 1, int(std::ceil(std::max({a[0], b[0], d[0]})))),
                    ya = std::max(0, int(std::floor(std::min({a[1], b[1], d[1]})))),
                    yb = std::min(H - 1, int(std::ceil(std::max({a[1], b[1], d[1]}))));
          for(int y = ya; y <= yb; ++y)
            for(int x = xa; x <= xb; ++x) {
              const double px = x + 0.5, py = y + 0.5;
              // Barycentric coordinates; pixel centers on an edge belong to both triangles (no cracks).
              const double l1 = ((px - a[0]) * (d[1] - a[1]) - (py - a[1]) * (d[0] - a[0])) / area;
              const double l2 = ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) / area;
              const double l0 = 1. - l1 - l2;
              if(l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
              const float z = float(l0 * a[2] + l1 * b[2] + l2 * d[2]);
              if(z <= depth[std::size_t(y) * W + x]) continue;
              Vec3 nv = normalized(l0 * vn[0] + l1 * vn[1] + l2 * vn[2]);
              if(dot(nv, nv) == 0) nv = face_normal;
              if(dot(nv, w) < 0) nv = -1. * nv;
              const Vec3 base = colored ? base_color(l0 * c.scalar[v[0]] + l1 * c.scalar[v[1]] + l2 * c.scalar[v[2]]) : material;
              put_pixel(x, y, z, shade(nv, base));
            }
        }
    } else {
      // Point set: one splat per point, the disc of radius `splat` x spacing on its tangent plane,
      // projected: an ellipse (a circle where the point faces the camera, a thin sliver at the
      // silhouette, where a full circle would stick out of the outline as a dark rim).
      const double radius = std::max(0.75, o.splat * c.spacing * scale);
      const int r = int(std::ceil(radius));
      for(std::size_t i = 0; i < c.points.size(); ++i) {
        const Vec3& p = c.points[i];
        if(!finite(p)) continue;
        Vec3 nv = i < c.normals.size() ? normalized(c.normals[i]) : Vec3{{0, 0, 0}};
        if(dot(nv, w) < 0) nv = -1. * nv;                       // two-sided: face the camera
        const Vec3 base = i < c.scalar.size() ? base_color(c.scalar[i]) : material;
        const Vec3 rgb = shade(nv, base);
        const Vec3 q = project(p);
        // Depth slope of the tangent plane; the splat stays at least 0.25 radius wide when seen edge-on
        // (nz >= 0.25), and a point without a normal gets a round splat.
        const double nz = std::max(0.25, dot(nv, w)), gx = -dot(nv, right) / nz, gy = dot(nv, up) / nz;
        const bool round = dot(nv, nv) == 0;
        const int px = int(std::floor(q[0])), py = int(std::floor(q[1]));
        for(int y = std::max(0, py - r); y <= std::min(H - 1, py + r); ++y)
          for(int x = std::max(0, px - r); x <= std::min(W - 1, px + r); ++x) {
            const double dx = x + 0.5 - q[0], dy = y + 0.5 - q[1], dz = round ? 0. : gx * dx + gy * dy;
            if(dx * dx + dy * dy + dz * dz > radius * radius) continue;
            put_pixel(x, y, float(q[2] + dz), rgb);
          }
      }
    }
    // Box-filter the supersampled panel into the image.
    for(int y = 0; y < o.height; ++y)
      for(int x = 0; x < pw; ++x)
        for(int k = 0; k < 3; ++k) {
          float s = 0.f;
          for(int j = 0; j < ss; ++j)
            for(int i = 0; i < ss; ++i) s += color[((std::size_t(y) * ss + j) * W + std::size_t(x) * ss + i) * 3 + k];
          image.rgb[(std::size_t(y) * image.width + std::size_t(panel) * pw + x) * 3 + k] =
            std::uint8_t(std::lround(255.f * s / float(ss * ss)));
        }
    if(panel > 0)   // thin separator between panels
      for(int y = 0; y < o.height; ++y)
        for(int k = 0; k < 3; ++k) image.rgb[(std::size_t(y) * image.width + std::size_t(panel) * pw) * 3 + k] = 200;
  }
  return image;
}

void write_png(const Image& image, const std::string& path)
{
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = PNG_FORMAT_RGB;
  if(!png_image_write_to_file(&png, path.c_str(), 0, image.rgb.data(), 0, nullptr))
    throw std::runtime_error(std::string("cannot write the PNG: ") + png.message);
}

Image read_png(const std::string& path)
{
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  if(!png_image_begin_read_from_file(&png, path.c_str()))
    throw std::runtime_error(std::string("not a readable PNG: ") + png.message);
  png.format = PNG_FORMAT_RGB;
  Image image;
  image.width = int(png.width);
  image.height = int(png.height);
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if(!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr))
    throw std::runtime_error(std::string("not a readable PNG: ") + png.message);
  return image;
}

// ---------------------------------------------------------------------------------------------
// Atomic output files. The interrupt handler removes the one temporary file in progress, if any.
namespace {
char g_temporary[4096] = {0};
} // namespace

void remove_output_files_on_interrupt() { remove_on_interrupt(g_temporary); }

Output_file::Output_file(const std::string& path) : path_(path)
{
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1 == 1 ? 1 : slash);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  if(base.empty()) throw std::runtime_error(path + ": names a folder, not a file");
  const std::string prefix = dir + "/." + base + ".tmp-";
  if(prefix.size() + 7 >= sizeof(g_temporary)) throw std::runtime_error(path + ": the path is too long");
  try {
    tmp_ = create_unique_file(prefix);
  } catch(const std::runtime_error& e) {
    throw std::runtime_error(path + ": cannot create a file in " + dir + " (" + e.what() + ")");
  }
  std::strcpy(g_temporary, tmp_.c_str());
}

Output_file::~Output_file()
{
  if(!committed_) std::remove(tmp_.c_str());
  g_temporary[0] = 0;
}

void Output_file::commit()
{
  if(std::rename(tmp_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error(path_ + ": cannot rename the temporary file to it (" + std::strerror(errno) + ")");
  committed_ = true;
  g_temporary[0] = 0;
}

} // namespace wavejets_demo
