// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_PARAMETERS_H
#define CGAL_WAVEJETS_PARAMETERS_H

// The package's own named parameters. They live in CGAL::Wavejets::parameters (never in
// CGAL::parameters: a future CGAL parameter of the same name would make every call ambiguous)
// and chain among themselves and then with CGAL's:
//   CGAL::Wavejets::parameters::order(8).maximum_displacement(d).evaluation_radius(s)
//                              .neighbor_radius(r).point_map(pm)
// After a CGAL parameter the pack is a plain CGAL pack, so put the package's parameters first,
// or prepend one to an existing pack with the two-argument form: order(3, ps.parameters()).

#include <CGAL/Named_function_parameters.h>

namespace CGAL {
namespace Wavejets {

/// \cond SKIP_IN_MANUAL
// X-macro: every package parameter, once. Documented in the functions that read them; their defaults
// are those of Fitting_options and function_defaults() (Function_defaults.h).
#define CGAL_WAVEJETS_PARAMETER_LIST(X)                                                            \
  X(order)                       /* K, the Wavejet order                                        */ \
  X(evaluation_radius)           /* s of a_n(s); default Rf                                     */ \
  X(maximum_displacement)        /* clamp of the position filter; default Rf/2, inf: off        */ \
  X(neighbors_per_coefficient)   /* beta of the adaptive order                                  */ \
  X(correction_iterations)       /* tangent-plane re-fits                                       */ \
  X(tangent_plane_order)         /* order of the tangent-plane search fits                      */ \
  X(robust_iterations)           /* Tukey IRLS passes                                           */ \
  X(minimum_order)               /* lowest order before the fit fails                           */ \
  X(curvature_frame)             /* Wavejets::Curvature_frame                                   */ \
  X(orient_with_input_normals)   /* estimate_normals: keep the input normals' orientation       */ \
  X(seed_with_input_normals)     /* first fit in the plane orthogonal to the input normal       */ \
  X(restrict_to_consistent_normals) /* drop neighbors whose normal is > 90 deg from the center's */ \
  X(use_neighbor_normals)        /* Hermite fit to heights and the neighbors' normals' slopes   */ \
  X(neighbor_normal_weight)      /* weight of the slope rows of the Hermite fit                 */ \
  X(compact_weights)             /* rows weighted by (1 - (d/Rf)^2)^2                           */ \
  X(write_normals)               /* enhance_positions: also write the Wavejet normals           */ \
  X(move_along_input_normals)    /* enhance_positions: move along the input normals             */ \
  X(fitted_map)                  /* writable bool map: true where a Wavejet was fitted          */ \
  X(neighborhood_size_map)       /* readable map: each point's number of neighbors (0: k)       */ \
  X(neighbor_radius_map)         /* readable map: each point's radius Rf (0: neighbor_radius)     */ \
  X(order_map)                   /* readable map: each point's order K (0: order)               */ \
  X(neighborhood_sizes)          /* estimate_scales: the ladder of numbers of neighbors         */ \
  X(scale_descriptor_map)        /* estimate_scales: writable map of each point's descriptor    */ \
  X(tile_size)                   /* tiled run: at most this many points per tile (0: in core)   */ \
  X(tile_halo)                   /* tiled run: first halo width of each tile (0: estimated)     */ \
  X(tile)                        /* Wavejets::Tile: the range is one tile of a larger point set */ \
  X(owned_map)                   /* with tile: readable bool map, the points to fit             */ \
  X(outside_map)                 /* with tile: writable bool map, fits that reach past the tile */ \
  X(mean_curvature_map)                                                                            \
  X(gaussian_curvature_map)                                                                        \
  X(maximal_principal_curvature_map)                                                               \
  X(minimal_principal_curvature_map)                                                               \
  X(maximal_principal_direction_map)                                                               \
  X(minimal_principal_direction_map)

namespace internal_np {
#define CGAL_WAVEJETS_DECLARE_TAG(name) enum name##_t { name };
CGAL_WAVEJETS_PARAMETER_LIST(CGAL_WAVEJETS_DECLARE_TAG)
#undef CGAL_WAVEJETS_DECLARE_TAG
} // namespace internal_np

/// A CGAL named-parameter pack (it derives from one, without data) whose members also
/// offer the package's parameters, so that they chain among themselves.
template <class T, class Tag, class Base = CGAL::internal_np::No_property>
struct Named_function_parameters : CGAL::Named_function_parameters<T, Tag, Base>
{
  typedef CGAL::Named_function_parameters<T, Tag, Base> Cgal_pack;
  Named_function_parameters(const T& v) : Cgal_pack(v) {}
  Named_function_parameters(const T& v, const Base& b) : Cgal_pack(v, b) {}

#define CGAL_WAVEJETS_MEMBER(name)                                                     \
  template <class K>                                                                   \
  Named_function_parameters<K, internal_np::name##_t, Cgal_pack> name(const K& k) const \
  {                                                                                    \
    return Named_function_parameters<K, internal_np::name##_t, Cgal_pack>(k, *this);   \
  }
  CGAL_WAVEJETS_PARAMETER_LIST(CGAL_WAVEJETS_MEMBER)
#undef CGAL_WAVEJETS_MEMBER
};
/// \endcond

namespace parameters {

/// \cond SKIP_IN_MANUAL
// For each parameter: name(v) starts a pack; name(v, np) prepends it onto an existing CGAL pack.
#define CGAL_WAVEJETS_FREE_FUNCTION(name)                                                          \
  template <class K>                                                                               \
  Wavejets::Named_function_parameters<K, internal_np::name##_t> name(const K& k)                   \
  {                                                                                                \
    return Wavejets::Named_function_parameters<K, internal_np::name##_t>(k);                       \
  }                                                                                                \
  template <class K, class T, class Tag, class Base>                                               \
  Wavejets::Named_function_parameters<K, internal_np::name##_t,                                    \
                                      CGAL::Named_function_parameters<T, Tag, Base> >              \
  name(const K& k, const CGAL::Named_function_parameters<T, Tag, Base>& np)                        \
  {                                                                                                \
    return Wavejets::Named_function_parameters<K, internal_np::name##_t,                           \
                                               CGAL::Named_function_parameters<T, Tag, Base> >(k, np); \
  }
CGAL_WAVEJETS_PARAMETER_LIST(CGAL_WAVEJETS_FREE_FUNCTION)
#undef CGAL_WAVEJETS_FREE_FUNCTION
/// \endcond

} // namespace parameters
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_PARAMETERS_H
