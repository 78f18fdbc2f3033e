// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef WAVEJETS_TEST_SUPPORT_H
#define WAVEJETS_TEST_SUPPORT_H

// The test harness shared by every test of test/Wavejets (header-only, the standard library and
// CGAL's kernel types only):
// - checks: check(ok, what) and CHECK(cond, streamed what) count every check executed and failed,
//   per case and in all; check_printed(ok, what) and report(name, ok, numbers) are checks that
//   print their line either way; begin_section/end_section print one line per part of a case;
// - named cases: run_cases(argc, argv, cases) runs every case, or with an argument only the case
//   of that name or the cases of that group (name "group.case"); --list prints the names. Each
//   case ends with one line: PASS/FAIL, its name, checks executed and failed. CTest registers one
//   entry per group (test/Wavejets/CMakeLists.txt), so `ctest -R test_robustness.class` runs one;
// - bitwise comparison (same_bits) of doubles, points, vectors, pairs and vectors of them;
// - Gauss: a portable deterministic standard normal;
// - Vector_slot_map: a read-write property map keyed by the elements of a std::vector (by
//   address) that stores its values in another std::vector;
// The analytic surfaces with their exact normals and curvatures (tests and benchmarks) are in
// analytic_surfaces.h.

#include <boost/property_map/property_map.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
template <class R> class Point_3;
template <class R> class Vector_3;
} // namespace CGAL

namespace wavejets_test {

// ------------------------------------------------------------------------------------------------
// Checks

struct Counts
{
  long checks = 0, failures = 0;
};
inline Counts& all_counts() { static Counts c; return c; }
inline Counts& case_counts() { static Counts c; return c; }
inline Counts& section_counts() { static Counts c; return c; }
inline std::string& case_name() { static std::string n; return n; }
inline std::string& section_name() { static std::string n; return n; }

/// Counts one check; prints `what` if it failed (the first 25 failures of a case). Returns `ok`.
inline bool check(bool ok, const std::string& what)
{
  ++all_counts().checks;
  ++case_counts().checks;
  ++section_counts().checks;
  if(!ok)
  {
    ++all_counts().failures;
    ++section_counts().failures;
    if(++case_counts().failures <= 25)
      std::cout << "    FAIL [" << (section_name().empty() ? case_name() : section_name()) << "]: " << what << std::endl;
  }
  return ok;
}

/// A check that prints its line whether it passed or not: `what`.
inline bool check_printed(bool ok, const std::string& what)
{
  check(ok, what);
  std::cout << (ok ? "  [ OK ] " : "  [FAIL] ") << what << std::endl;
  return ok;
}

/// A check that prints its line whether it passed or not: `name: numbers`.
inline bool report(const std::string& name, bool ok, const std::string& numbers)
{
  return check_printed(ok, name + ": " + numbers);
}

/// `x` with `digits` significant digits (printf's %.*g).
inline std::string significant_digits(double x, int digits)
{
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, x);
  return b;
}

/// Sections of a case: begin_section(name) ... end_section(info) prints one line with the
/// section's checks executed and failed, and `info`.
inline void begin_section(const std::string& name)
{
  section_name() = name;
  section_counts() = Counts();
}
inline void end_section(const std::string& info = "")
{
  const Counts& n = section_counts();
  std::cout << "  " << (n.failures == 0 ? "PASS " : "FAIL ") << section_name() << " (" << n.checks << " checks"
            << (n.failures ? ", " + std::to_string(n.failures) + " failed" : std::string()) << ")"
            << (info.empty() ? "" : ": " + info) << std::endl;
  section_name().clear();
}

} // namespace wavejets_test

/// CHECK(cond, what): a check whose description is streamed (`"x " << x`), built only on failure.
#define CHECK(cond, what)                                                                          \
  do {                                                                                             \
    if(cond) ::wavejets_test::check(true, std::string());                                          \
    else                                                                                           \
    {                                                                                              \
      std::ostringstream wavejets_check_what_;                                                     \
      wavejets_check_what_ << what << " (" #cond ")";                                              \
      ::wavejets_test::check(false, wavejets_check_what_.str());                                   \
    }                                                                                              \
  } while(0)

namespace wavejets_test {

// ------------------------------------------------------------------------------------------------
// Named cases

struct Case
{
  std::string name; // "group.case" or "group"
  std::function<void()> run;
};

inline std::string group_of(const std::string& name) { return name.substr(0, name.find('.')); }

/// Runs `cases` in order: all of them, or with argv[1] the case of that name or the cases of that
/// group; `--list` prints the group names, one a line. Returns the process exit status: failure
/// if a check failed, a case threw, or the name matches no case.
inline int run_cases(int argc, char** argv, const std::vector<Case>& cases)
{
  const std::string selected = argc > 1 ? argv[1] : "";
  if(selected == "--list")
  {
    std::string last;
    for(const Case& c : cases)
      if(group_of(c.name) != last) std::cout << (last = group_of(c.name)) << "\n";
    return EXIT_SUCCESS;
  }
  std::size_t run = 0;
  for(const Case& c : cases)
  {
    if(!selected.empty() && c.name != selected && group_of(c.name) != selected) continue;
    ++run;
    case_name() = c.name;
    case_counts() = Counts();
    try { c.run(); }
    catch(const std::exception& e) { check(false, std::string("unexpected exception: ") + e.what()); }
    const Counts& n = case_counts();
    std::cout << (n.failures ? "FAIL " : "PASS ") << c.name << " (" << n.checks << " checks, " << n.failures
              << " failed)" << std::endl;
  }
  if(run == 0)
  {
    std::cout << "no case named " << selected << " (--list prints them)" << std::endl;
    return EXIT_FAILURE;
  }
  const Counts& a = all_counts();
  std::cout << run << " case(s), " << a.checks << " checks executed, " << a.failures << " failed" << std::endl;
  return a.failures ? EXIT_FAILURE : EXIT_SUCCESS;
}

// ------------------------------------------------------------------------------------------------
// Bitwise comparison

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }
template <class K>
bool same_bits(const CGAL::Point_3<K>& a, const CGAL::Point_3<K>& b)
{ return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z()); }
template <class K>
bool same_bits(const CGAL::Vector_3<K>& a, const CGAL::Vector_3<K>& b)
{ return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z()); }
template <class A, class B>
bool same_bits(const std::pair<A, B>& a, const std::pair<A, B>& b)
{ return same_bits(a.first, b.first) && same_bits(a.second, b.second); }
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b)
{
  if(a.size() != b.size()) return false;
  for(std::size_t i = 0; i < a.size(); ++i)
    if(!same_bits(a[i], b[i])) return false;
  return true;
}
/// Byte equality of two vectors of trivially copyable values.
template <class T>
bool bitwise_equal(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// ------------------------------------------------------------------------------------------------
// Random numbers

/// Portable deterministic standard normal (mt19937_64 is specified by the standard; the
/// distributions are not, so Box-Muller is written out).
struct Gauss
{
  std::mt19937_64 gen;
  explicit Gauss(std::uint64_t seed) : gen(seed) {}
  double uniform() { return (double(gen() >> 11) + 0.5) * (1. / 9007199254740992.); }
  double operator()()
  {
    return std::sqrt(-2. * std::log(uniform())) * std::cos(2. * 3.14159265358979323846 * uniform());
  }
};

// ------------------------------------------------------------------------------------------------
// Property map

/// Read-write property map keyed by the elements of a std::vector<Key> (by address), storing T in
/// a std::vector<T>: curvature outputs and fitted_map on std::vector inputs.
template <class Key, class T>
struct Vector_slot_map
{
  typedef Key key_type;
  typedef T value_type;
  typedef T& reference;
  typedef boost::read_write_property_map_tag category;
  const Key* base;
  std::vector<T>* data;
  friend void put(const Vector_slot_map& m, const Key& k, const T& v) { (*m.data)[std::size_t(&k - m.base)] = v; }
  friend T& get(const Vector_slot_map& m, const Key& k) { return (*m.data)[std::size_t(&k - m.base)]; }
};
/// Sizes `d` like `r` and returns the map from the elements of `r` to those of `d`.
template <class Key, class T>
Vector_slot_map<Key, T> slot_map(const std::vector<Key>& r, std::vector<T>& d)
{
  d.resize(r.size());
  return Vector_slot_map<Key, T>{r.data(), &d};
}

} // namespace wavejets_test

#endif // WAVEJETS_TEST_SUPPORT_H
