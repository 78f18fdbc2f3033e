// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_VERSION_H
#define CGAL_WAVEJETS_VERSION_H

/*!
\ingroup PkgWavejetsRef
\file CGAL/Wavejets/version.h
The version of the Wavejets package, for preprocessor tests such as
`#if CGAL_WAVEJETS_VERSION_NR >= 10100`. It matches `package_info/Wavejets/version`, the
version of the installed CMake package (`find_package(CGAL_Wavejets 1.1)`) and `wavejets --version`.
*/

/// Major version: changes that break the API.
#define CGAL_WAVEJETS_VERSION_MAJOR 1
/// Minor version: new features, compatible API.
#define CGAL_WAVEJETS_VERSION_MINOR 1
/// Patch version: fixes only.
#define CGAL_WAVEJETS_VERSION_PATCH 0
/// The version as a string, "MAJOR.MINOR.PATCH".
#define CGAL_WAVEJETS_VERSION_STR "1.1.0"
/// The version as one number, MAJOR * 10000 + MINOR * 100 + PATCH.
#define CGAL_WAVEJETS_VERSION_NR                                                                  \
  (CGAL_WAVEJETS_VERSION_MAJOR * 10000 + CGAL_WAVEJETS_VERSION_MINOR * 100 + CGAL_WAVEJETS_VERSION_PATCH)

#endif // CGAL_WAVEJETS_VERSION_H
