// SPDX-License-Identifier: GPL-3.0-or-later
// The streaming statistics of the accuracy report: Pearson's and the circular
// correlation, the error summary and Moran's I, against hand-computed values and
// independent direct formulas.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "tinlod/accuracy_statistics.h"

namespace tinlod {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180;

struct Pair {
  double a, b;
};

std::vector<Pair> randomPairs(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, 1);
  std::vector<Pair> pairs(n);
  for (Pair& p : pairs) {
    p.a = noise(rng);
    p.b = 0.6 * p.a + 0.8 * noise(rng);  // r about 0.6
  }
  return pairs;
}

PairStatistics pairStats(const std::vector<Pair>& pairs, std::size_t begin = 0, std::size_t end = SIZE_MAX) {
  PairStatistics s;
  for (std::size_t i = begin; i < std::min(end, pairs.size()); ++i) s.add(pairs[i].a, pairs[i].b);
  return s;
}

CircularPairStatistics circularStats(const std::vector<Pair>& pairs, std::size_t begin = 0,
                                     std::size_t end = SIZE_MAX) {
  CircularPairStatistics s;
  for (std::size_t i = begin; i < std::min(end, pairs.size()); ++i) s.add(pairs[i].a, pairs[i].b);
  return s;
}

void expectSamePairStatistics(const PairStatistics& x, const PairStatistics& y, double tolerance) {
  EXPECT_EQ(x.count(), y.count());
  EXPECT_NEAR(x.correlation(), y.correlation(), tolerance);
  EXPECT_NEAR(x.meanA(), y.meanA(), tolerance);
  EXPECT_NEAR(x.meanB(), y.meanB(), tolerance);
  EXPECT_NEAR(x.stdA(), y.stdA(), tolerance);
  EXPECT_NEAR(x.stdB(), y.stdB(), tolerance);
}

// Distance on the circle, so that 359.9999 and 0 are close.
double angularDistance(double a, double b) {
  const double d = std::fmod(std::fabs(a - b), 360.0);
  return std::min(d, 360 - d);
}

// Jammalamadaka and Sarma's r the direct way, two passes: the circular means first.
double directCircularCorrelation(const std::vector<Pair>& pairs) {
  double sa = 0, ca = 0, sb = 0, cb = 0;
  for (const Pair& p : pairs) {
    sa += std::sin(p.a * kRadiansPerDegree), ca += std::cos(p.a * kRadiansPerDegree);
    sb += std::sin(p.b * kRadiansPerDegree), cb += std::cos(p.b * kRadiansPerDegree);
  }
  const double meanA = std::atan2(sa, ca), meanB = std::atan2(sb, cb);
  double ab = 0, aa = 0, bb = 0;
  for (const Pair& p : pairs) {
    const double da = std::sin(p.a * kRadiansPerDegree - meanA), db = std::sin(p.b * kRadiansPerDegree - meanB);
    ab += da * db, aa += da * da, bb += db * db;
  }
  return ab / std::sqrt(aa * bb);
}

Grid gridOf(int cols, int rows, const std::vector<double>& values) {
  Grid g(cols, rows);
  g.values = values;
  return g;
}

// Moran's I straight from its definition, visiting each point's four neighbours.
double directMoransI(const Grid& g) {
  double sum = 0;
  int n = 0;
  for (double v : g.values)
    if (!std::isnan(v)) sum += v, ++n;
  const double mean = sum / n;
  double numerator = 0, denominator = 0, weights = 0;
  const int dc[] = {1, -1, 0, 0}, dr[] = {0, 0, 1, -1};
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      if (!g.valid(c, r)) continue;
      denominator += (g.at(c, r) - mean) * (g.at(c, r) - mean);
      for (int k = 0; k < 4; ++k) {
        const int c2 = c + dc[k], r2 = r + dr[k];
        if (c2 < 0 || r2 < 0 || c2 >= g.cols || r2 >= g.rows || !g.valid(c2, r2)) continue;
        numerator += (g.at(c, r) - mean) * (g.at(c2, r2) - mean);
        weights += 1;
      }
    }
  return n / weights * numerator / denominator;
}

}  // namespace

// ---- PairStatistics -------------------------------------------------------------

TEST(PairStatistics, IdenticalSeriesCorrelateOneWithEqualMeansAndStds) {
  PairStatistics s;
  for (const Pair& p : randomPairs(1000, 1)) s.add(p.a, p.a);
  EXPECT_NEAR(s.correlation(), 1, 1e-12);
  EXPECT_EQ(s.meanA(), s.meanB());
  EXPECT_EQ(s.stdA(), s.stdB());
  EXPECT_GT(s.stdA(), 0.5);
}

TEST(PairStatistics, LinearRelationsCorrelatePlusOrMinusOne) {
  PairStatistics up, down;
  for (const Pair& p : randomPairs(1000, 2)) up.add(p.a, 2 * p.a + 3), down.add(p.a, -p.a);
  EXPECT_NEAR(up.correlation(), 1, 1e-12);
  EXPECT_NEAR(up.meanB(), 2 * up.meanA() + 3, 1e-12);
  EXPECT_NEAR(up.stdB(), 2 * up.stdA(), 1e-12);
  EXPECT_NEAR(down.correlation(), -1, 1e-12);
  EXPECT_NEAR(down.meanB(), -down.meanA(), 1e-12);
}

TEST(PairStatistics, HandComputedFivePairs) {
  // a = 1 2 3 4 5, mean 3, deviations -2 -1 0 1 2: sum of squares 10.
  // b = 2 4 5 4 5, mean 4, deviations -2  0 1 0 1: sum of squares 6.
  // Sum of products 4 + 0 + 0 + 0 + 2 = 6, so r = 6 / sqrt(10 * 6) = sqrt(0.6);
  // population stds sqrt(10 / 5) = sqrt(2) and sqrt(6 / 5) = sqrt(1.2).
  PairStatistics s;
  const double a[] = {1, 2, 3, 4, 5}, b[] = {2, 4, 5, 4, 5};
  for (int i = 0; i < 5; ++i) s.add(a[i], b[i]);
  EXPECT_EQ(s.count(), 5u);
  EXPECT_NEAR(s.correlation(), std::sqrt(0.6), 1e-12);
  EXPECT_NEAR(s.meanA(), 3, 1e-12);
  EXPECT_NEAR(s.meanB(), 4, 1e-12);
  EXPECT_NEAR(s.stdA(), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s.stdB(), std::sqrt(1.2), 1e-12);
}

TEST(PairStatistics, PairsWithANaNAreSkipped) {
  const std::vector<Pair> pairs = randomPairs(100, 3);
  PairStatistics withNaNs = pairStats(pairs);
  withNaNs.add(kNaN, 1);
  withNaNs.add(1, kNaN);
  withNaNs.add(kNaN, kNaN);
  EXPECT_EQ(withNaNs.count(), 100u);
  expectSamePairStatistics(withNaNs, pairStats(pairs), 0);
}

TEST(PairStatistics, MergingHalvesEqualsOnePass) {
  const std::vector<Pair> pairs = randomPairs(1001, 4);
  PairStatistics merged = pairStats(pairs, 0, 317);  // uneven parts: the weights matter
  merged.merge(pairStats(pairs, 317));
  expectSamePairStatistics(merged, pairStats(pairs), 1e-12);
}

TEST(PairStatistics, MergingAnEmptyAccumulatorChangesNothing) {
  const std::vector<Pair> pairs = randomPairs(50, 5);
  PairStatistics intoFull = pairStats(pairs), intoEmpty;
  intoFull.merge(PairStatistics());
  intoEmpty.merge(pairStats(pairs));
  expectSamePairStatistics(intoFull, pairStats(pairs), 0);
  expectSamePairStatistics(intoEmpty, pairStats(pairs), 0);
}

TEST(PairStatistics, LargeOffsetLosesNoDigits) {
  // Elevations of 1e6 m with differences of about a metre: sum(x^2) - n mean^2 would
  // cancel 12 of 16 digits; the co-moments about the running means keep them.
  const std::vector<Pair> pairs = randomPairs(10000, 6);
  PairStatistics offset;
  for (const Pair& p : pairs) offset.add(1e6 + p.a, 1e6 + p.b);
  const PairStatistics centred = pairStats(pairs);
  EXPECT_NEAR(offset.correlation(), centred.correlation(), 1e-9);
  EXPECT_NEAR(offset.stdA(), centred.stdA(), 1e-9);
  EXPECT_NEAR(offset.stdB(), centred.stdB(), 1e-9);
  // The mean itself carries the offset: about a rounding of 1e6 (1e-10) per step.
  EXPECT_NEAR(offset.meanA(), 1e6 + centred.meanA(), 1e-13 * 1e6);
}

TEST(PairStatistics, UndefinedCorrelationIsNaN) {
  PairStatistics empty, one, constant;
  EXPECT_TRUE(std::isnan(empty.correlation()));
  EXPECT_TRUE(std::isnan(empty.meanA()));
  EXPECT_TRUE(std::isnan(empty.stdB()));
  one.add(1, 2);
  EXPECT_TRUE(std::isnan(one.correlation()));
  EXPECT_EQ(one.stdA(), 0);
  for (int i = 0; i < 10; ++i) constant.add(i, 0.1);  // 0.1: not exact in binary
  EXPECT_TRUE(std::isnan(constant.correlation()));
  EXPECT_EQ(constant.stdB(), 0);
}

// ---- CircularPairStatistics -----------------------------------------------------

TEST(CircularPairStatistics, IdenticalAnglesCorrelateOne) {
  CircularPairStatistics s;
  for (int i = 0; i < 100; ++i) s.add(i * 3.3, i * 3.3);
  EXPECT_NEAR(s.correlation(), 1, 1e-12);
  EXPECT_NEAR(s.meanA(), s.meanB(), 1e-12);
  EXPECT_NEAR(s.stdA(), s.stdB(), 1e-12);
}

TEST(CircularPairStatistics, ShiftedAnglesCorrelateOneWithShiftedMean) {
  // Angles over half the circle, shifted by 30 degrees across 360.
  CircularPairStatistics s;
  for (int i = 0; i < 100; ++i) s.add(200 + i * 1.7, std::fmod(230 + i * 1.7, 360.0));
  EXPECT_NEAR(s.correlation(), 1, 1e-12);
  EXPECT_NEAR(angularDistance(s.meanB(), s.meanA() + 30), 0, 1e-9);
  EXPECT_NEAR(s.stdA(), s.stdB(), 1e-9);
}

TEST(CircularPairStatistics, MeanWrapsAroundNorth) {
  // The arithmetic mean of 350 and 10 is 180, the circular mean north; the spread is
  // sqrt(-2 ln cos 10 deg) radians.
  CircularPairStatistics s;
  s.add(350, 10);
  s.add(10, 350);
  const double mean = s.meanA();
  EXPECT_GE(mean, 0);
  EXPECT_LT(mean, 360);
  EXPECT_NEAR(angularDistance(mean, 0), 0, 1e-9);
  EXPECT_NEAR(s.stdA(), std::sqrt(-2 * std::log(std::cos(10 * kRadiansPerDegree))) / kRadiansPerDegree, 1e-9);
  EXPECT_NEAR(s.correlation(), -1, 1e-12);  // each swaps sides of north
}

TEST(CircularPairStatistics, HandComputedThreePairs) {
  // a = 0, 90, 45: resultant (sin, cos) sums (1 + s, 1 + s), s = sin 45 = 1/sqrt 2, so the
  // mean is 45, R = sqrt 2 (1 + s) = 1 + sqrt 2, Rbar = (1 + sqrt 2) / 3;
  // sin(a - 45) = -s, s, 0, sum of squares 1.
  // b = 30, 60, 90: mean 60 by symmetry, R = 1 + 2 cos 30 = 1 + sqrt 3, Rbar = (1 + sqrt 3) / 3;
  // sin(b - 60) = -1/2, 0, 1/2, sum of squares 1/2.
  // Sum of products s / 2 + 0 + 0, so r = (s / 2) / sqrt(1 * 1/2) = 1/2.
  CircularPairStatistics s;
  s.add(0, 30);
  s.add(90, 60);
  s.add(45, 90);
  EXPECT_EQ(s.count(), 3u);
  EXPECT_NEAR(s.correlation(), 0.5, 1e-12);
  EXPECT_NEAR(s.meanA(), 45, 1e-12);
  EXPECT_NEAR(s.meanB(), 60, 1e-12);
  const auto stdDegrees = [](double rbar) { return std::sqrt(-2 * std::log(rbar)) / kRadiansPerDegree; };
  EXPECT_NEAR(s.stdA(), stdDegrees((1 + std::sqrt(2.0)) / 3), 1e-12);
  EXPECT_NEAR(s.stdB(), stdDegrees((1 + std::sqrt(3.0)) / 3), 1e-12);
}

TEST(CircularPairStatistics, MatchesTheTwoPassFormulaAndMergesExactly) {
  std::vector<Pair> pairs = randomPairs(2000, 7);
  for (Pair& p : pairs) p.a = std::fmod(p.a * 40 + 720, 360.0), p.b = std::fmod(p.b * 40 + 700, 360.0);
  const CircularPairStatistics one = circularStats(pairs);
  EXPECT_NEAR(one.correlation(), directCircularCorrelation(pairs), 1e-12);
  EXPECT_GT(one.correlation(), 0.3);  // a real correlation, not a degenerate one
  CircularPairStatistics merged = circularStats(pairs, 0, 777);
  merged.merge(circularStats(pairs, 777));
  merged.merge(CircularPairStatistics());
  EXPECT_EQ(merged.count(), one.count());
  EXPECT_NEAR(merged.correlation(), one.correlation(), 1e-12);
  EXPECT_NEAR(merged.meanA(), one.meanA(), 1e-12);
  EXPECT_NEAR(merged.meanB(), one.meanB(), 1e-12);
  EXPECT_NEAR(merged.stdA(), one.stdA(), 1e-12);
  EXPECT_NEAR(merged.stdB(), one.stdB(), 1e-12);
}

TEST(CircularPairStatistics, NaNsAreSkippedAndAConstantSideHasNoCorrelation) {
  CircularPairStatistics s;
  for (int i = 0; i < 100; ++i) s.add(i * 3.0, 123.4);
  s.add(kNaN, 10);  // flat ground has no aspect
  s.add(10, kNaN);
  EXPECT_EQ(s.count(), 100u);
  EXPECT_TRUE(std::isnan(s.correlation()));
  EXPECT_NEAR(s.meanB(), 123.4, 1e-9);
  EXPECT_NEAR(s.stdB(), 0, 1e-5);  // R rounds to 1 - 1 ulp at best: 1e-6 degrees
  EXPECT_TRUE(std::isnan(CircularPairStatistics().meanA()));
}

// ---- ErrorStatistics ------------------------------------------------------------

TEST(ErrorStatistics, AlternatingErrorsHaveRmseOneAndMeanZero) {
  ErrorStatistics s;
  for (int i = 0; i < 1000; ++i) s.add(i % 2 ? -1 : 1, i, 2 * i, 999 - i);
  EXPECT_EQ(s.count(), 1000u);
  EXPECT_DOUBLE_EQ(s.rmse(), 1);
  EXPECT_EQ(s.mean(), 0);
  EXPECT_EQ(s.maxAbs(), 1);
  EXPECT_EQ(s.maxX(), 999);  // every |e| ties: the point first in row order, added last
  EXPECT_EQ(s.maxY(), 1998);
}

TEST(ErrorStatistics, LargestAbsoluteErrorAndItsLocation) {
  ErrorStatistics s;
  s.add(0.5, 1, 1, 0);
  s.add(-3, 7, 8, 1);  // the largest in absolute value is negative
  s.add(2.5, 9, 9, 2);
  s.add(kNaN, 5, 5, 3);
  EXPECT_EQ(s.count(), 3u);
  EXPECT_EQ(s.maxAbs(), 3);
  EXPECT_EQ(s.maxX(), 7);
  EXPECT_EQ(s.maxY(), 8);
  EXPECT_NEAR(s.mean(), 0, 1e-15);
  EXPECT_NEAR(s.rmse(), std::sqrt((0.25 + 9 + 6.25) / 3), 1e-15);
}

TEST(ErrorStatistics, MergeKeepsTheLargerMaximumAndOnTiesTheFirstInRowOrder) {
  ErrorStatistics a, b, c;
  a.add(2, 1, 1, 7);
  b.add(-2, 2, 2, 4);
  c.add(5, 3, 3, 9);
  ErrorStatistics ab = a, ba = b;
  ab.merge(b), ba.merge(a);  // a tie: b's point comes first in row order, whichever merges
  EXPECT_EQ(ab.maxX(), 2);
  EXPECT_EQ(ba.maxX(), 2);
  ab.merge(c);  // larger: c's
  EXPECT_EQ(ab.maxX(), 3);
  EXPECT_EQ(ab.maxAbs(), 5);
  EXPECT_EQ(ab.count(), 3u);
  EXPECT_NEAR(ab.mean(), 5.0 / 3, 1e-15);
  ErrorStatistics empty;
  empty.merge(b);
  EXPECT_EQ(empty.maxX(), 2);
  EXPECT_TRUE(std::isnan(ErrorStatistics().rmse()));
  EXPECT_TRUE(std::isnan(ErrorStatistics().maxAbs()));
}

TEST(ErrorStatistics, TiesGoToTheFirstPointInRowOrderWhateverOrderTheyComeIn) {
  // A 4 x 3 raster whose errors tie at three points; added in row order, backwards, and as
  // two pieces merged either way round (as a catalogue's tiles are).
  const double errors[12] = {1, 3, 0, -3, 2, 3, 0, 1, 0, 0, -1, 2};
  const auto addRange = [&](ErrorStatistics& s, int begin, int end, int step) {
    for (int i = begin; i != end; i += step) s.add(errors[i], i % 4, i / 4, std::uint64_t(i));
  };
  ErrorStatistics forward, backward, firstRow, otherRows;
  addRange(forward, 0, 12, 1);
  addRange(backward, 11, -1, -1);
  addRange(firstRow, 0, 4, 1), addRange(otherRows, 4, 12, 1);
  ErrorStatistics firstRowMerged = firstRow, otherRowsMerged = otherRows;
  firstRowMerged.merge(otherRows), otherRowsMerged.merge(firstRow);
  for (const ErrorStatistics* s : {&forward, &backward, &firstRowMerged, &otherRowsMerged}) {
    EXPECT_EQ(s->maxAbs(), 3);
    EXPECT_EQ(s->maxX(), 1);  // point 1, before points 3 and 5
    EXPECT_EQ(s->maxY(), 0);
  }
}

TEST(ErrorStatistics, MillionsOfErrorsSumWithoutDrift) {
  // 0.1 is not exact in binary; added 4 M times in plain double the mean is off by 5e-12
  // (5e-11 relative). The compensated sum keeps it to a rounding or two.
  ErrorStatistics s;
  for (int i = 0; i < 4000000; ++i) s.add(0.1, 0, 0, i);
  EXPECT_NEAR(s.mean(), 0.1, 1e-16);
  EXPECT_NEAR(s.rmse(), 0.1, 1e-16);
}

// ---- Moran's I ------------------------------------------------------------------

TEST(MoransI, HandComputedThreeByThree) {
  // 1 2 3 / 4 5 6 / 7 8 9: mean 5, deviations -4 .. 4, sum of squares 2 (16 + 9 + 4 + 1) = 60.
  // Horizontal pairs: 12 + 6 (row 1), 0 + 0 (row 2), 6 + 12 (row 3) = 36.
  // Vertical pairs: 4 - 2 (column 1), 0 + 0 (column 2), -2 + 4 (column 3) = 4.
  // 12 pairs, so W = 24 and sum w_ij z_i z_j = 2 * 40 = 80: I = 9 / 24 * 80 / 60 = 0.5.
  const Grid g = gridOf(3, 3, {1, 2, 3, 4, 5, 6, 7, 8, 9});
  EXPECT_NEAR(moransI(g), 0.5, 1e-12);
}

TEST(MoransI, HandComputedWithAHole) {
  // The same without the centre: 8 points, mean still 5, sum of squares still 60.
  // Horizontal pairs: 12 + 6 (row 1), none (row 2), 6 + 12 (row 3) = 36.
  // Vertical pairs: 4 - 2 (column 1), none (column 2), -2 + 4 (column 3) = 4.
  // 8 pairs, W = 16: I = 8 / 16 * 80 / 60 = 2 / 3. (A NaN read as 0 would give 11 / 37.)
  const Grid g = gridOf(3, 3, {1, 2, 3, 4, kNaN, 6, 7, 8, 9});
  EXPECT_NEAR(moransI(g), 2.0 / 3, 1e-12);
}

TEST(MoransI, CheckerboardIsMinusOne) {
  // Every pair joins a high and a low point: with n0 low and n1 high points the mean's
  // deviations are -n1 / N and n0 / N (times the step), each pair contributes
  // -n0 n1 / N^2, the sum of squares is n0 n1 / N and I = N / P * (-P n0 n1 / N^2) /
  // (n0 n1 / N) = -1 for any size. 10 and 20 on an even board: mean 15, all exact.
  Grid even(8, 6), odd(7, 5);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 8; ++c) even.at(c, r) = (r + c) % 2 ? 10 : 20;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 7; ++c) odd.at(c, r) = (r + c) % 2 ? 0.3 : 1.7;
  EXPECT_EQ(moransI(even), -1);
  EXPECT_NEAR(moransI(odd), -1, 1e-12);  // mean 34 / 35 of the way: rounded
}

TEST(MoransI, SmoothGradientIsStronglyPositive) {
  Grid g(100, 80);
  for (int r = 0; r < 80; ++r)
    for (int c = 0; c < 100; ++c) g.at(c, r) = 1000 + 2.0 * c - 3.0 * r;
  EXPECT_GT(moransI(g), 0.95);
  EXPECT_NEAR(moransI(g), directMoransI(g), 1e-12);
}

TEST(MoransI, MatchesTheDefinitionWithRandomHoles) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> value(-5, 5);
  Grid g(37, 23);
  for (double& v : g.values) v = value(rng) < -3 ? kNaN : value(rng);
  const double i = moransI(g);
  EXPECT_NEAR(i, directMoransI(g), 1e-12);
  EXPECT_LT(std::fabs(i), 0.2);  // noise: no autocorrelation
}

// Moran's I summed over pieces of a grid, each adding its own points and the pairs with its
// right and lower neighbours, as the tiles of a catalogue do.
double moransIByPieces(const Grid& g, int pieceCols, int pieceRows) {
  MoranAccumulator total;
  for (int r0 = 0; r0 < g.rows; r0 += pieceRows)
    for (int c0 = 0; c0 < g.cols; c0 += pieceCols) {
      MoranAccumulator piece;
      for (int r = r0; r < std::min(g.rows, r0 + pieceRows); ++r)
        for (int c = c0; c < std::min(g.cols, c0 + pieceCols); ++c) {
          if (!g.valid(c, r)) continue;
          piece.addPoint(g.at(c, r));
          if (c + 1 < g.cols && g.valid(c + 1, r)) piece.addPair(g.at(c, r), g.at(c + 1, r));
          if (r + 1 < g.rows && g.valid(c, r + 1)) piece.addPair(g.at(c, r), g.at(c, r + 1));
        }
      total.merge(piece);
    }
  return total.value();
}

TEST(MoranAccumulator, PiecesMergedAreTheWholeGridsMoransI) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> value(-5, 5);
  Grid noise(37, 23), smooth(37, 23);
  for (double& v : noise.values) v = value(rng) < -3 ? kNaN : value(rng);
  for (int r = 0; r < 23; ++r)
    for (int c = 0; c < 37; ++c) smooth.at(c, r) = std::sin(c / 5.0) + 0.1 * r + (c * r % 7 == 0 ? kNaN : 0);
  for (const Grid* g : {&noise, &smooth})
    for (const auto& [cols, rows] : {std::pair{37, 23}, std::pair{10, 7}, std::pair{1, 1}, std::pair{5, 23}})
      EXPECT_NEAR(moransIByPieces(*g, cols, rows), directMoransI(*g), 1e-12) << cols << " x " << rows;
  EXPECT_GT(moransIByPieces(smooth, 10, 7), 0.8);
}

TEST(MoranAccumulator, CheckerboardIsMinusOneAndUndefinedCasesAreNaN) {
  Grid checkerboard(6, 5);
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 6; ++c) checkerboard.at(c, r) = (r + c) % 2 ? 1 : -1;
  EXPECT_NEAR(moransIByPieces(checkerboard, 4, 2), -1, 1e-12);
  EXPECT_TRUE(std::isnan(MoranAccumulator().value()));
  EXPECT_TRUE(std::isnan(moransIByPieces(Grid(4, 3, 0.1), 2, 2)));                      // constant
  EXPECT_TRUE(std::isnan(moransIByPieces(gridOf(2, 2, {0.1, kNaN, 0.1, 0.1}), 1, 1)));  // constant with a hole
  EXPECT_TRUE(std::isnan(moransIByPieces(gridOf(2, 2, {1, kNaN, kNaN, 2}), 1, 1)));     // no neighbours
  MoranAccumulator one;
  one.addPoint(3);
  MoranAccumulator merged;
  merged.merge(MoranAccumulator());  // an empty piece changes nothing
  merged.merge(one);
  EXPECT_TRUE(std::isnan(merged.value()));  // one point
}

TEST(MoransI, UndefinedCasesAreNaN) {
  EXPECT_TRUE(std::isnan(moransI(Grid())));
  EXPECT_TRUE(std::isnan(moransI(Grid(4, 3, 0.1))));                     // constant
  EXPECT_TRUE(std::isnan(moransI(gridOf(2, 2, {0.1, kNaN, 0.1, 0.1}))));   // constant with a hole
  EXPECT_TRUE(std::isnan(moransI(gridOf(2, 2, {1, kNaN, kNaN, kNaN}))));   // one point
  EXPECT_TRUE(std::isnan(moransI(gridOf(2, 2, {1, kNaN, kNaN, 2}))));      // no neighbours
  EXPECT_TRUE(std::isnan(moransI(Grid(3, 3))));                          // all NaN
}

}  // namespace tinlod
