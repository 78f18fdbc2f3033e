// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_TILE_H
#define CGAL_WAVEJETS_TILE_H

#include <CGAL/Bbox_3.h>

namespace CGAL {
namespace Wavejets {

/// \ingroup PkgWavejetsRef
/// One tile of a point set that is not held in one range (on disk, or spread over machines), the
/// unit of work of a tiled run (\ref Wavejets_tiles). Passed with `Wavejets::parameters::tile(t)`,
/// it tells a function that its range holds every point of the whole point set that lies in the
/// closed box `extent`, in their order in the whole point set (so that neighbors at the same distance
/// are ranked by index as in one piece), and nothing else. The function then fits the points of its
/// `Wavejets::parameters::owned_map` (all, without one) and writes a result only where it is the
/// result of the whole point set, bit for bit: the points whose neighborhood reaches past `extent`
/// are not fitted and are marked in `Wavejets::parameters::outside_map` (and counted in the report);
/// fit them again in a tile with a larger extent.
struct Tile
{
  /// The closed box whose points the range holds: the box of the owned points grown by a halo.
  Bbox_3 extent;
  /// The bounding box of every finite point of the whole point set (no point lies beyond it, so
  /// a neighborhood may reach past the sides of `extent` that lie beyond it).
  Bbox_3 bounds;
};

} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_TILE_H
