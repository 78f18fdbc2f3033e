// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef WAVEJETS_BENCH_PONCA_TYPES_H
#define WAVEJETS_BENCH_PONCA_TYPES_H

// Benchmark only: the Ponca types of bench_ponca_accuracy (accuracy) and bench_speed (APSS's time
// on the same neighborhoods as the Wavejet fits). Ponca (https://github.com/poncateam/ponca,
// MPL-2.0) is never used by the package; benchmark/Wavejets/CMakeLists.txt defines
// WAVEJETS_HAVE_PONCA where it finds it. Without it this header declares nothing.

#ifdef WAVEJETS_HAVE_PONCA
#include <Ponca/Fitting>

#include <Eigen/Core>

/// Ponca's point type: position and normal.
struct Ponca_point
{
  enum { Dim = 3 };
  typedef double Scalar;
  typedef Eigen::Matrix<Scalar, Dim, 1> VectorType;
  typedef Eigen::Matrix<Scalar, Dim, Dim> MatrixType;
  PONCA_MULTIARCH inline Ponca_point(const VectorType& p = VectorType::Zero(), const VectorType& n = VectorType::Zero())
    : m_pos(p), m_normal(n)
  {}
  PONCA_MULTIARCH inline const VectorType& pos() const { return m_pos; }
  PONCA_MULTIARCH inline const VectorType& normal() const { return m_normal; }
  VectorType m_pos, m_normal;
};
typedef Ponca::DistWeightFunc<Ponca_point, Ponca::ConstantWeightKernel<double> > Constant_weight;
typedef Ponca::DistWeightFunc<Ponca_point, Ponca::SmoothWeightKernel<double> > Smooth_weight;
typedef Ponca::Basket<Ponca_point, Constant_weight, Ponca::OrientedSphereFit, Ponca::GLSParam> APSS_constant;
typedef Ponca::Basket<Ponca_point, Smooth_weight, Ponca::OrientedSphereFit, Ponca::GLSParam> APSS_smooth;
typedef Ponca::BasketDiff<Ponca::Basket<Ponca_point, Smooth_weight, Ponca::OrientedSphereFit>, Ponca::FitSpaceDer,
                          Ponca::OrientedSphereDer, Ponca::MlsSphereFitDer, Ponca::CurvatureEstimatorDer,
                          Ponca::NormalDerivativeWeingartenEstimator, Ponca::WeingartenCurvatureEstimatorDer>
  ASO_smooth;
#endif // WAVEJETS_HAVE_PONCA

#endif // WAVEJETS_BENCH_PONCA_TYPES_H
