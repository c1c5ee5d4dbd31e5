// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_statistics.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace tinlod {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadiansPerDegree = kPi / 180;

// Rounding can push a correlation computed from sums a few ulps past +-1.
double clampCorrelation(double r) { return std::clamp(r, -1.0, 1.0); }

// The direction of a resultant vector in degrees in [0, 360); NaN without a direction.
double directionDegrees(double sinSum, double cosSum) {
  if (sinSum == 0 && cosSum == 0) return kNaN;
  double degrees = std::atan2(sinSum, cosSum) / kRadiansPerDegree;
  if (degrees < 0) degrees += 360;
  // -1e-17 + 360 rounds to 360, which is 0 on the circle.
  return degrees >= 360 ? degrees - 360 : degrees;
}

// Circular standard deviation sqrt(-2 ln R) in degrees from the resultant's components.
double circularStdDegrees(double sinSum, double cosSum, std::size_t count) {
  if (count == 0) return kNaN;
  // Rounding can make R of identical angles exceed 1 by an ulp; ln must not go positive.
  const double meanResultant = std::min(1.0, std::hypot(sinSum, cosSum) / double(count));
  return std::sqrt(-2 * std::log(meanResultant)) / kRadiansPerDegree;
}

}  // namespace

// ---- PairStatistics -------------------------------------------------------------

void PairStatistics::add(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return;
  ++count_;
  const double n = double(count_);
  const double da = a - meanA_;  // deviations from the old means
  const double db = b - meanB_;
  meanA_ += da / n;
  meanB_ += db / n;
  // Old deviation times new deviation: Welford's update, exact in exact arithmetic and
  // free of the cancellation of sum(x^2) - n mean^2.
  m2a_ += da * (a - meanA_);
  m2b_ += db * (b - meanB_);
  cab_ += da * (b - meanB_);
}

void PairStatistics::merge(const PairStatistics& other) {
  if (other.count_ == 0) return;
  if (count_ == 0) {
    *this = other;
    return;
  }
  // Chan, Golub and LeVeque: the co-moments about the combined means are the parts'
  // co-moments plus the spread between the parts' means, weighted by na nb / n.
  const double na = double(count_), nb = double(other.count_), n = na + nb;
  const double da = other.meanA_ - meanA_;
  const double db = other.meanB_ - meanB_;
  const double weight = na * nb / n;
  meanA_ += da * (nb / n);
  meanB_ += db * (nb / n);
  m2a_ += other.m2a_ + da * da * weight;
  m2b_ += other.m2b_ + db * db * weight;
  cab_ += other.cab_ + da * db * weight;
  count_ += other.count_;
}

double PairStatistics::correlation() const {
  // A constant side has m2 exactly 0: Welford's deviations of equal values are exact.
  if (count_ < 2 || !(m2a_ > 0) || !(m2b_ > 0)) return kNaN;
  // sqrt of each factor, not of the product, which could overflow or underflow.
  return clampCorrelation(cab_ / (std::sqrt(m2a_) * std::sqrt(m2b_)));
}

double PairStatistics::meanA() const { return count_ ? meanA_ : kNaN; }
double PairStatistics::meanB() const { return count_ ? meanB_ : kNaN; }
double PairStatistics::stdA() const { return count_ ? std::sqrt(m2a_ / double(count_)) : kNaN; }
double PairStatistics::stdB() const { return count_ ? std::sqrt(m2b_ / double(count_)) : kNaN; }

// ---- CircularPairStatistics -----------------------------------------------------

void CircularPairStatistics::add(double aDegrees, double bDegrees) {
  if (std::isnan(aDegrees) || std::isnan(bDegrees)) return;
  ++count_;
  const double sa = std::sin(aDegrees * kRadiansPerDegree), ca = std::cos(aDegrees * kRadiansPerDegree);
  const double sb = std::sin(bDegrees * kRadiansPerDegree), cb = std::cos(bDegrees * kRadiansPerDegree);
  sa_.add(sa), ca_.add(ca), sb_.add(sb), cb_.add(cb);
  sasb_.add(sa * sb), sacb_.add(sa * cb), casb_.add(ca * sb), cacb_.add(ca * cb);
  sa2_.add(sa * sa), ca2_.add(ca * ca), saca_.add(sa * ca);
  sb2_.add(sb * sb), cb2_.add(cb * cb), sbcb_.add(sb * cb);
}

void CircularPairStatistics::merge(const CircularPairStatistics& other) {
  using Self = CircularPairStatistics;
  static constexpr detail::CompensatedSum Self::*kSums[] = {
      &Self::sa_,   &Self::ca_,   &Self::sb_,  &Self::cb_,  &Self::sasb_, &Self::sacb_, &Self::casb_,
      &Self::cacb_, &Self::sa2_, &Self::ca2_, &Self::saca_, &Self::sb2_, &Self::cb2_, &Self::sbcb_};
  count_ += other.count_;
  for (auto sum : kSums) (this->*sum).merge(other.*sum);
}

double CircularPairStatistics::correlation() const {
  if (count_ < 2) return kNaN;
  // Unit vectors of the mean directions; their angle is all the sums need.
  const double ra = std::hypot(sa_.value(), ca_.value()), rb = std::hypot(sb_.value(), cb_.value());
  if (ra == 0 || rb == 0) return kNaN;
  const double sma = sa_.value() / ra, cma = ca_.value() / ra;
  const double smb = sb_.value() / rb, cmb = cb_.value() / rb;
  // sin(a - a') = sin a cos a' - cos a sin a', summed in products over the pairs.
  const double sab = sasb_.value() * cma * cmb - sacb_.value() * cma * smb - casb_.value() * sma * cmb +
                     cacb_.value() * sma * smb;
  const double saa = sa2_.value() * cma * cma - 2 * saca_.value() * cma * sma + ca2_.value() * sma * sma;
  const double sbb = sb2_.value() * cmb * cmb - 2 * sbcb_.value() * cmb * smb + cb2_.value() * smb * smb;
  // The expansion cancels to a few ulps of the count for a constant side, not to 0;
  // anything that small is no spread (64 eps per pair: an RMS spread below 7e-6 degrees).
  const double noSpread = 64 * std::numeric_limits<double>::epsilon() * double(count_);
  if (!(saa > noSpread) || !(sbb > noSpread)) return kNaN;
  return clampCorrelation(sab / (std::sqrt(saa) * std::sqrt(sbb)));
}

double CircularPairStatistics::meanA() const { return count_ ? directionDegrees(sa_.value(), ca_.value()) : kNaN; }
double CircularPairStatistics::meanB() const { return count_ ? directionDegrees(sb_.value(), cb_.value()) : kNaN; }
double CircularPairStatistics::stdA() const { return circularStdDegrees(sa_.value(), ca_.value(), count_); }
double CircularPairStatistics::stdB() const { return circularStdDegrees(sb_.value(), cb_.value(), count_); }

// ---- ErrorStatistics ------------------------------------------------------------

void ErrorStatistics::add(double error, double x, double y, std::uint64_t order) {
  if (std::isnan(error)) return;
  if (beats(std::fabs(error), order)) maxAbs_ = std::fabs(error), maxX_ = x, maxY_ = y, maxOrder_ = order;
  ++count_;
  sum_.add(error);
  sumSquares_.add(error * error);
}

void ErrorStatistics::merge(const ErrorStatistics& other) {
  if (other.count_ == 0) return;
  if (beats(other.maxAbs_, other.maxOrder_))
    maxAbs_ = other.maxAbs_, maxX_ = other.maxX_, maxY_ = other.maxY_, maxOrder_ = other.maxOrder_;
  count_ += other.count_;
  sum_.merge(other.sum_);
  sumSquares_.merge(other.sumSquares_);
}

double ErrorStatistics::rmse() const { return count_ ? std::sqrt(sumSquares_.value() / double(count_)) : kNaN; }
double ErrorStatistics::mean() const { return count_ ? sum_.value() / double(count_) : kNaN; }
double ErrorStatistics::maxAbs() const { return count_ ? maxAbs_ : kNaN; }
double ErrorStatistics::maxX() const { return count_ ? maxX_ : kNaN; }
double ErrorStatistics::maxY() const { return count_ ? maxY_ : kNaN; }

// ---- Moran's I ------------------------------------------------------------------

namespace {

struct ValidMean {
  std::size_t count = 0;
  double mean = kNaN;
  bool constant = true;  // all valid values equal: no variance, whatever the mean's rounding
};

ValidMean validMean(const std::vector<double>& values) {
  ValidMean m;
  detail::CompensatedSum sum;
  double first = kNaN;
  for (double v : values) {
    if (std::isnan(v)) continue;
    if (m.count++ == 0) first = v;
    m.constant = m.constant && v == first;
    sum.add(v);
  }
  if (m.count) m.mean = sum.value() / double(m.count);
  return m;
}

// One grid row as deviations from the mean, 0 at invalid points, which then drop out
// of every cross product without a test in the inner loops; valid[] says which count.
// Returns the row's sum of squared deviations.
double deviationRow(const double* values, int cols, double mean, double* deviation, unsigned char* valid) {
  double squares = 0;
  for (int c = 0; c < cols; ++c) {
    const bool ok = !std::isnan(values[c]);
    deviation[c] = ok ? values[c] - mean : 0;
    valid[c] = ok;
    squares += deviation[c] * deviation[c];
  }
  return squares;
}

// Cross products and pair count of the element-wise neighbours in two rows, or in one
// row and itself shifted by one (horizontal pairs): a[c] with b[c], c < n.
void addPairs(const double* a, const unsigned char* aValid, const double* b, const unsigned char* bValid, int n,
              double& cross, std::uint64_t& pairs) {
  double sum = 0;
  std::uint64_t count = 0;
  for (int c = 0; c < n; ++c) {
    sum += a[c] * b[c];
    count += aValid[c] & bValid[c];
  }
  cross += sum;
  pairs += count;
}

}  // namespace

double moransI(const Grid& field) {
  const ValidMean m = validMean(field.values);
  // A constant field's mean may round off its value, leaving tiny deviations whose
  // ratio would be about 1 rather than undefined: decide that case exactly.
  if (m.count < 2 || m.constant) return kNaN;
  const int cols = field.cols;
  // Two rows of deviations: the current one and the one above (vertical neighbours).
  std::vector<double> above(cols), current(cols);
  std::vector<unsigned char> aboveValid(cols), currentValid(cols);
  double squares = 0, cross = 0;  // cross: each neighbouring pair once
  std::uint64_t pairs = 0;
  for (int row = 0; row < field.rows; ++row) {
    const double* values = field.values.data() + std::size_t(row) * cols;
    squares += deviationRow(values, cols, m.mean, current.data(), currentValid.data());
    addPairs(current.data(), currentValid.data(), current.data() + 1, currentValid.data() + 1, cols - 1, cross, pairs);
    if (row > 0) addPairs(above.data(), aboveValid.data(), current.data(), currentValid.data(), cols, cross, pairs);
    std::swap(above, current);
    std::swap(aboveValid, currentValid);
  }
  if (pairs == 0 || !(squares > 0)) return kNaN;
  // Both directions of every pair: sum w_ij z_i z_j = 2 cross and W = 2 pairs; the 2s cancel.
  return double(m.count) / double(pairs) * cross / squares;
}

void MoranAccumulator::addPoint(double value) {
  min_ = count_ ? std::min(min_, value) : value;
  max_ = count_ ? std::max(max_, value) : value;
  ++count_;
  sum_.add(value);
  squares_.add(value * value);
}

void MoranAccumulator::addPair(double a, double b) {
  ++pairs_;
  products_.add(a * b);
  pairSums_.add(a + b);
}

void MoranAccumulator::merge(const MoranAccumulator& other) {
  if (other.count_ == 0) return;
  min_ = count_ ? std::min(min_, other.min_) : other.min_;
  max_ = count_ ? std::max(max_, other.max_) : other.max_;
  count_ += other.count_, pairs_ += other.pairs_;
  sum_.merge(other.sum_), squares_.merge(other.squares_);
  products_.merge(other.products_), pairSums_.merge(other.pairSums_);
}

double MoranAccumulator::value() const {
  if (count_ < 2 || min_ == max_ || pairs_ == 0) return kNaN;
  const double n = double(count_), mean = sum_.value() / n;
  // sum (e - m)^2 = sum e^2 - n m^2; over the pairs, sum (a - m)(b - m) = sum ab - m sum (a + b) + pairs m^2.
  const double squares = squares_.value() - sum_.value() * mean;
  const double cross = products_.value() - mean * pairSums_.value() + double(pairs_) * mean * mean;
  if (!(squares > 0)) return kNaN;
  return n / double(pairs_) * cross / squares;
}

}  // namespace tinlod
