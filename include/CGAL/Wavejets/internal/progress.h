// Copyright (c) 2026 The CGAL Wavejets project.
// All rights reserved.
//
// This file is part of the CGAL Wavejets package.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : The CGAL Wavejets developers

#ifndef CGAL_WAVEJETS_INTERNAL_PROGRESS_H
#define CGAL_WAVEJETS_INTERNAL_PROGRESS_H

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>

namespace CGAL {
namespace Wavejets {
namespace internal {

/// Progress of one pass over `size` points, reported to the `callback` named parameter, and its
/// interruption (the callback returned `false`).
///
/// The threads that process the points report it themselves: after each chunk of points, the
/// thread that finds no other call in progress calls the callback, so there is never more than one
/// call at a time and no thread of its own. (CGAL's `Callback_wrapper<Parallel_tag>` starts a thread
/// that polls the progress every 10 microseconds: on two cores it made a call on 10^6 points take
/// 1.14x to 1.29x as long, however little the callback did.) Under `Sequential_tag` the one thread
/// calls it after each chunk. When the pass ends, `finish()` calls it once more with 1.
///
/// A pass over one tile of a tiled run (tiled_driver.h) has the run's progress as its `parent`: it
/// passes its points on to it, and stops when the run is interrupted.
class Pass_progress
{
public:
  Pass_progress(const std::function<bool(double)>& callback, std::size_t size, Pass_progress* parent = nullptr)
    : m_callback(callback), m_size(size), m_parent(parent) {}

  /// Whether the callback (or the parent's) has returned `false` (checked before each point).
  bool interrupted() const
  {
    return m_interrupted.load(std::memory_order_relaxed) || (m_parent && m_parent->interrupted());
  }

  /// `count` more points are done; calls the callback unless another thread is calling it.
  void advance(std::size_t count)
  {
    if(m_parent) m_parent->advance(count);
    const std::size_t done = m_done.fetch_add(count, std::memory_order_relaxed) + count;
    if(m_callback && !m_calling.test_and_set(std::memory_order_acquire))
    {
      report(double(done) / double(m_size));
      m_calling.clear(std::memory_order_release);
    }
  }

  /// The end of the pass (every thread has stopped): the last call, with 1, unless interrupted.
  /// A `false` returned there still interrupts.
  void finish()
  {
    if(m_callback && !interrupted()) report(1.);
  }

private:
  void report(double fraction)
  {
    // A tiled run counts the points fitted again with a larger halo twice: at most 1 all the same.
    if(!m_callback((std::min)(fraction, 1.))) m_interrupted.store(true, std::memory_order_relaxed);
  }

  const std::function<bool(double)>& m_callback;
  const std::size_t m_size;
  Pass_progress* const m_parent;
  alignas(64) std::atomic<std::size_t> m_done{0};    // written once per chunk by every thread
  alignas(64) std::atomic<bool> m_interrupted{false}; // read before every point
  std::atomic_flag m_calling = ATOMIC_FLAG_INIT;
};

} // namespace internal
} // namespace Wavejets
} // namespace CGAL

#endif // CGAL_WAVEJETS_INTERNAL_PROGRESS_H
