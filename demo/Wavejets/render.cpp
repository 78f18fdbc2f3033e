// Headless splat renderer and atomic output files of the `wavejets` tool (see render.h).
#include "render.h"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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

} // namespace

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
  const Vec3 half = normalized(light + w);

  const int n = int(clouds.size());
  const int ss = 2;                                               // supersampling per axis
  const int pw = o.width / n, W = pw * ss, H = o.height * ss;
  if(pw < 8) throw std::invalid_argument("image too narrow for the panels");

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
    const double radius = std::max(0.75, o.splat * c.spacing * scale);
    const int r = int(std::ceil(radius));
    for(std::size_t i = 0; i < c.points.size(); ++i) {
      const Vec3& p = c.points[i];
      if(!finite(p)) continue;
      Vec3 nv = i < c.normals.size() ? normalized(c.normals[i]) : Vec3{{0, 0, 0}};
      if(dot(nv, w) < 0) nv = -1. * nv;                       // two-sided: face the camera
      const double diffuse = std::max(0., dot(nv, light));
      const double specular = 0.18 * std::pow(std::max(0., dot(nv, half)), 40.);
      Vec3 base = {{0.78, 0.76, 0.70}};
      if(i < c.scalar.size())
        base = std::isfinite(c.scalar[i]) ? diverging(smax > 0 ? c.scalar[i] / smax : 0.) : Vec3{{0.5, 0.5, 0.5}};
      const Vec3 shade = (0.22 + 0.78 * diffuse) * base + Vec3{{specular, specular, specular}};
      const double sx = (dot(p, right) - cx) * scale + 0.5 * W, sy = 0.5 * H - (dot(p, up) - cy) * scale;
      const double d = dot(p, w) * scale;
      // Surfel: depth varies across the splat along its tangent plane (flat when seen edge-on).
      const double nz = dot(nv, w), gx = nz > 0.3 ? -dot(nv, right) / nz : 0., gy = nz > 0.3 ? dot(nv, up) / nz : 0.;
      const int px = int(std::floor(sx)), py = int(std::floor(sy));
      for(int y = std::max(0, py - r); y <= std::min(H - 1, py + r); ++y)
        for(int x = std::max(0, px - r); x <= std::min(W - 1, px + r); ++x) {
          const double dx = x + 0.5 - sx, dy = y + 0.5 - sy;
          if(dx * dx + dy * dy > radius * radius) continue;
          const float z = float(d + gx * dx + gy * dy);
          float& zb = depth[std::size_t(y) * W + x];
          if(z <= zb) continue;
          zb = z;
          for(int k = 0; k < 3; ++k) color[(std::size_t(y) * W + x) * 3 + k] = float(std::min(1., shade[k]));
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
// Atomic output files. The signal handler removes the one temporary file in progress, if any.
namespace {
char g_temporary[4096] = {0};
extern "C" void remove_temporary_and_exit(int sig)
{
  if(g_temporary[0] != 0) unlink(g_temporary);
  const char msg[] = "\nwavejets: interrupted, nothing written\n";
  ssize_t ignored = write(2, msg, sizeof(msg) - 1);
  (void)ignored;
  _exit(128 + sig);
}
} // namespace

Output_file::Output_file(const std::string& path) : path_(path)
{
  static bool handlers = false;
  if(!handlers) {
    std::signal(SIGINT, remove_temporary_and_exit);
    std::signal(SIGTERM, remove_temporary_and_exit);
    handlers = true;
  }
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1 == 1 ? 1 : slash);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  if(base.empty()) throw std::runtime_error(path + ": names a folder, not a file");
  std::string pattern = dir + "/." + base + ".tmp-XXXXXX";
  if(pattern.size() >= sizeof(g_temporary)) throw std::runtime_error(path + ": the path is too long");
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const int fd = mkstemp(buffer.data());
  if(fd < 0) throw std::runtime_error(path + ": cannot create a file in " + dir + " (" + std::strerror(errno) + ")");
  const mode_t mask = umask(0);
  umask(mask);
  if(fchmod(fd, 0666 & ~mask) != 0) { /* keep the 0600 of mkstemp */ }
  close(fd);
  tmp_ = buffer.data();
  std::strcpy(g_temporary, tmp_.c_str());
}

Output_file::~Output_file()
{
  if(!committed_) unlink(tmp_.c_str());
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
