// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "tinlod/grid.h"

namespace tinlod {

namespace detail {

// Neumaier's compensated sum: a sum of millions of terms (a grid of ~6 M test points)
// stays accurate to about one rounding of the result, on every platform (long double is
// no wider than double with MSVC or on ARM64). Inline: it sits in per-point loops.
// Relies on strict IEEE arithmetic; -ffast-math would optimise the compensation away.
class CompensatedSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    // The low-order bits lost in t are recovered from whichever operand is larger.
    compensation_ += std::fabs(sum_) >= std::fabs(x) ? (sum_ - t) + x : (x - t) + sum_;
    sum_ = t;
  }
  void merge(const CompensatedSum& other) {
    add(other.sum_);
    add(other.compensation_);
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0, compensation_ = 0;
};

}  // namespace detail

// Streaming comparison of paired values (reference a, simplified b): Pearson's r and
// each side's mean and standard deviation, numerically stable (Welford's co-moments,
// so values far from zero, such as elevations of 1000 m with centimetre differences,
// lose no digits). Pairs with a NaN on either side are skipped. Accumulators of
// different threads merge exactly as if all pairs had gone through one (Chan et al.).
// Everything but count() is NaN for an empty accumulator.
class PairStatistics {
 public:
  void add(double a, double b);
  void merge(const PairStatistics& other);
  std::size_t count() const { return count_; }
  double correlation() const;  // NaN with fewer than 2 pairs or a constant side; within [-1, 1]
  double meanA() const;
  double meanB() const;
  double stdA() const;         // population standard deviation (divides by the count)
  double stdB() const;

 private:
  std::size_t count_ = 0;
  double meanA_ = 0, meanB_ = 0;
  double m2a_ = 0, m2b_ = 0;   // sums of squared deviations from the running means
  double cab_ = 0;             // sum of products of the deviations
};

// The same for angles in degrees (aspect): the circular correlation coefficient of
// Jammalamadaka and Sarma, r = sum sin(a - a') sin(b - b') / sqrt(sum sin^2(a - a')
// sum sin^2(b - b')) about the circular means a', b'; the circular means in degrees
// in [0, 360); the circular standard deviations sqrt(-2 ln R), R the mean resultant
// length, in degrees. Streaming although r needs the final means: it is expanded into
// sums of products of the sines and cosines, so merging is adding sums. Pairs with a
// NaN (aspect of flat ground) are skipped. correlation() is NaN with fewer than 2 pairs
// or a side whose spread is lost in rounding (under about 1e-5 degrees: a constant angle);
// the means are NaN when the angles cancel exactly (no mean direction) and everything
// but count() is NaN for an empty accumulator.
class CircularPairStatistics {
 public:
  void add(double aDegrees, double bDegrees);
  void merge(const CircularPairStatistics& other);
  std::size_t count() const { return count_; }
  double correlation() const;
  double meanA() const;
  double meanB() const;
  double stdA() const;
  double stdB() const;

 private:
  std::size_t count_ = 0;
  // Sums over the pairs; s = sin, c = cos of a or b.
  detail::CompensatedSum sa_, ca_, sb_, cb_;
  detail::CompensatedSum sasb_, sacb_, casb_, cacb_;
  detail::CompensatedSum sa2_, ca2_, saca_, sb2_, cb2_, sbcb_;
};

// Elevation error e = simplified - reference at located points: RMSE, mean error and
// the largest absolute error with the location where it occurs. NaN errors are skipped.
// Sums are compensated, so millions of points lose no accuracy. All results but count()
// are NaN for an empty accumulator.
class ErrorStatistics {
 public:
  // `order`: the point's place in the raster's row order (row x columns + column). Where
  // errors tie, the location is the one of smallest order, in whatever order the points
  // were added and the parts merged: a raster measured a tile at a time reports the
  // location measured whole.
  void add(double error, double x, double y, std::uint64_t order);
  void merge(const ErrorStatistics& other);
  std::size_t count() const { return count_; }
  double rmse() const;
  double mean() const;
  double maxAbs() const;
  double maxX() const;
  double maxY() const;

 private:
  std::size_t count_ = 0;
  detail::CompensatedSum sum_, sumSquares_;
  double maxAbs_ = 0, maxX_ = 0, maxY_ = 0;  // meaningful once count_ > 0
  std::uint64_t maxOrder_ = 0;
  bool beats(double absError, std::uint64_t order) const {
    return count_ == 0 || absError > maxAbs_ || (absError == maxAbs_ && order < maxOrder_);
  }
};

// Moran's I of a field on a grid with binary rook (4-neighbour) weights between valid
// points: I = (N / W) sum_ij w_ij (e_i - m)(e_j - m) / sum_i (e_i - m)^2, N the valid
// points, m their mean, w_ij = 1 for valid horizontal or vertical neighbours (each
// pair in both directions, so W = 2 x the neighbouring pairs). NaN (invalid) points
// take no part: they are neither counted nor anybody's neighbour. -1 for a full
// checkerboard, near +1 for a smooth field, near 0 for noise. NaN when fewer than 2
// valid points, no neighbouring pairs or a constant field. Two passes over the grid.
double moransI(const Grid& field);

// Moran's I as above from points and neighbouring pairs added in any order, in parts that
// merge: for a grid measured a piece at a time, each piece adding its own points and the
// pairs it owns (with its right and lower neighbours, which may lie in the next piece).
// It expands the deviations into compensated sums of the values, their squares and their
// products; against the two passes of moransI it loses about log10(mean^2 / variance)
// digits, none that matter for an error field. NaN in the same cases as moransI.
class MoranAccumulator {
 public:
  void addPoint(double value);
  void addPair(double a, double b);  // both valid points, each also given to addPoint
  void merge(const MoranAccumulator& other);
  double value() const;

 private:
  std::size_t count_ = 0;
  std::uint64_t pairs_ = 0;
  double min_ = 0, max_ = 0;  // meaningful once count_ > 0: a constant field has no I
  detail::CompensatedSum sum_, squares_, products_, pairSums_;
};

}  // namespace tinlod
