#include "drillwave/integration/hermite_history.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drillwave/integration/quartic.hpp"

namespace drillwave::integration {
namespace {

// Query times computed as (t + tau) - tau miss a stored boundary by a few ulps; closer than this they are on it.
double SnapTolerance(double t) { return 1e-12 * std::max(1.0, std::abs(t)); }

// Pieces Locate walks from its last answer before it searches.
constexpr int kWalk = 4;

}  // namespace

double QuarterPointError(int n, double h, const double* x0, const double* x1, const double* d0, const double* d1,
                         const double* x_mid, const double* x_quarter, double abs_tol, double rel_tol) {
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    const double stored = QuarticValue(0.25, h, x0[i], x1[i], d0[i], d1[i], BubbleWeight(h, x0[i], x1[i], d0[i], d1[i], x_mid[i]));
    const double scale = abs_tol + rel_tol * std::max(std::abs(x0[i]), std::abs(x1[i]));
    worst = std::max(worst, std::abs(x_quarter[i] - stored) / scale);
  }
  return worst;
}

HermiteHistory::HermiteHistory(int dimension)
    : HermiteHistory(dimension, [dimension](double, double* x, double* d) {
        std::fill(x, x + dimension, 0.0);
        std::fill(d, d + dimension, 0.0);
      }) {}

HermiteHistory::HermiteHistory(int dimension, Prehistory prehistory)
    : dimension_(dimension),
      prehistory_(std::move(prehistory)),
      scratch_value_(dimension),
      scratch_deriv_(dimension) {
  if (dimension <= 0) throw std::invalid_argument("HermiteHistory: dimension must be positive");
}

double HermiteHistory::begin_time() const { return empty() ? 0.0 : t_begin_[first_]; }
double HermiteHistory::end_time() const { return empty() ? 0.0 : t_end_.back(); }

void HermiteHistory::Append(double t0, const double* x0, const double* d0, double t1, const double* x1,
                            const double* d1, const double* x_mid, bool restart) {
  if (!(t1 > t0)) throw std::invalid_argument("HermiteHistory::Append: empty or reversed piece");
  if (!empty()) {
    t0 = t_end_.back();  // keep the pieces contiguous despite rounding in the caller's times
    if (!(t1 > t0)) return;  // a piece within rounding of the end: nothing to add
  }
  // A value or slope that differs by more than rounding from the last end's (a rate recomputed after a breakpoint
  // differs by that) or, for the very first piece, from the prehistory's.
  const double *last_x1 = nullptr, *last_d1 = nullptr;
  if (!empty()) {
    last_x1 = PieceData(t_begin_.size() - 1) + dimension_;
    last_d1 = last_x1 + 2 * dimension_;
  } else if (t_begin_.empty()) {
    origin_.resize(2 * dimension_);
    prehistory_(t0, origin_.data(), origin_.data() + dimension_);
    last_x1 = origin_.data(), last_d1 = origin_.data() + dimension_;
  }
  auto differs = [](double a, double b) { return std::abs(a - b) > 1e-12 * std::max(std::abs(a), std::abs(b)); };
  if (restart && !empty()) {
    kinked_.push_back(t_begin_.size());
  } else if (last_x1) {
    for (int i = 0; i < dimension_; ++i)
      if (differs(d0[i], last_d1[i]) || differs(x0[i], last_x1[i])) {
        kinked_.push_back(t_begin_.size());
        break;
      }
  }
  t_begin_.push_back(t0);
  t_end_.push_back(t1);
  const std::size_t at = data_.size();
  const int n = dimension_;
  data_.resize(at + kPerPiece * n);
  double* piece = data_.data() + at;
  const double h = t1 - t0;
  for (int i = 0; i < n; ++i) {
    piece[i] = x0[i], piece[n + i] = x1[i], piece[2 * n + i] = d0[i], piece[3 * n + i] = d1[i];
    piece[4 * n + i] = BubbleWeight(h, x0[i], x1[i], d0[i], d1[i], x_mid[i]);
  }
}

HermiteHistory::Location HermiteHistory::Locate(double t, Side side) const {
  if (empty()) return {kPrehistory, 0.0};
  const double eps = SnapTolerance(t);
  // Look-ups come in runs at nearby times (a step's stages, a node's waves at the quarter, middle and end of a piece):
  // walk a few pieces from the one found last time, and search only when the time is further away.
  const std::size_t n = t_begin_.size();
  std::size_t piece = std::min(std::max(hint_, first_), n - 1);
  int walked = 0;
  while (walked < kWalk && piece + 1 < n && t_begin_[piece + 1] <= t + eps) ++piece, ++walked;
  while (walked < kWalk && piece > first_ && t_begin_[piece] > t + eps) --piece, ++walked;
  if (walked == kWalk) {
    // Last piece starting at or before t + eps: t lies on its start boundary (within eps) or inside it.
    const auto begin = t_begin_.begin() + static_cast<std::ptrdiff_t>(first_);
    const auto it = std::upper_bound(begin, t_begin_.end(), t + eps);
    if (it == begin) return {kPrehistory, 0.0};
    piece = static_cast<std::size_t>(it - t_begin_.begin()) - 1;
  }
  if (t_begin_[piece] > t + eps) return {kPrehistory, 0.0};  // before the history (piece == first_)
  hint_ = piece;
  if (std::abs(t - t_begin_[piece]) <= eps) {
    // On a boundary: the left limit lives in the previous piece (or the prehistory).
    if (side == Side::kLeft) {
      if (piece == first_) return {kPrehistory, 0.0};
      --piece;
      return {piece, 1.0};
    }
    return {piece, 0.0};
  }
  const double h = t_end_[piece] - t_begin_[piece];
  return {piece, (t - t_begin_[piece]) / h};
}

double HermiteHistory::Value(double t, int i, Side side) const {
  const Location loc = Locate(t, side);
  if (loc.piece == kPrehistory) {
    prehistory_(std::min(t, empty() ? t : begin_time()), scratch_value_.data(), scratch_deriv_.data());
    return scratch_value_[i];
  }
  const double* p = PieceData(loc.piece);
  const int n = dimension_;
  return QuarticValue(loc.s, t_end_[loc.piece] - t_begin_[loc.piece], p[i], p[n + i], p[2 * n + i], p[3 * n + i], p[4 * n + i]);
}

double HermiteHistory::Derivative(double t, int i, Side side) const {
  const Location loc = Locate(t, side);
  if (loc.piece == kPrehistory) {
    prehistory_(std::min(t, empty() ? t : begin_time()), scratch_value_.data(), scratch_deriv_.data());
    return scratch_deriv_[i];
  }
  const double* p = PieceData(loc.piece);
  const int n = dimension_;
  return QuarticDerivative(loc.s, t_end_[loc.piece] - t_begin_[loc.piece], p[i], p[n + i], p[2 * n + i],
                           p[3 * n + i], p[4 * n + i]);
}

void HermiteHistory::Values(double t, double* out, Side side) const {
  const Location loc = Locate(t, side);
  if (loc.piece == kPrehistory) {
    prehistory_(std::min(t, empty() ? t : begin_time()), out, scratch_deriv_.data());
    return;
  }
  const double* p = PieceData(loc.piece);
  const int n = dimension_;
  const double h = t_end_[loc.piece] - t_begin_[loc.piece];
  for (int i = 0; i < n; ++i) out[i] = QuarticValue(loc.s, h, p[i], p[n + i], p[2 * n + i], p[3 * n + i], p[4 * n + i]);
}

void HermiteHistory::Derivatives(double t, double* out, Side side) const {
  const Location loc = Locate(t, side);
  if (loc.piece == kPrehistory) {
    prehistory_(std::min(t, empty() ? t : begin_time()), scratch_value_.data(), out);
    return;
  }
  const double* p = PieceData(loc.piece);
  const int n = dimension_;
  const double h = t_end_[loc.piece] - t_begin_[loc.piece];
  for (int i = 0; i < n; ++i)
    out[i] = QuarticDerivative(loc.s, h, p[i], p[n + i], p[2 * n + i], p[3 * n + i], p[4 * n + i]);
}

void HermiteHistory::ValuesAndDerivatives(double t, double* value, double* derivative, Side side) const {
  const Location loc = Locate(t, side);
  if (loc.piece == kPrehistory) {
    prehistory_(std::min(t, empty() ? t : begin_time()), value, derivative);
    return;
  }
  const double* p = PieceData(loc.piece);
  const int n = dimension_;
  const double h = t_end_[loc.piece] - t_begin_[loc.piece];
  for (int i = 0; i < n; ++i) {
    value[i] = QuarticValue(loc.s, h, p[i], p[n + i], p[2 * n + i], p[3 * n + i], p[4 * n + i]);
    derivative[i] = QuarticDerivative(loc.s, h, p[i], p[n + i], p[2 * n + i], p[3 * n + i], p[4 * n + i]);
  }
}

double HermiteHistory::IntegrateSquare(int i, double a, double b) const {
  static constexpr double kNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                       0.9061798459386640};
  static constexpr double kWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                         0.4786286704993665, 0.2369268850561891};
  double total = 0;
  auto integrate = [&](double lo, double hi) {
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (int q = 0; q < 5; ++q) {
      const double v = Value(mid + half * kNodes[q], i);
      total += kWeights[q] * half * v * v;
    }
  };
  double lo = a;
  // Prehistory part (constant or user function): integrate it as one smooth piece.
  if (empty() || lo < t_begin_[first_]) {
    const double hi = empty() ? b : std::min(b, t_begin_[first_]);
    if (hi > lo) integrate(lo, hi);
    lo = std::max(lo, hi);
  }
  for (std::size_t p = first_; p < t_begin_.size() && lo < b; ++p) {
    if (t_end_[p] <= lo) continue;
    const double hi = std::min(b, t_end_[p]);
    if (hi > lo) integrate(lo, hi);
    lo = hi;
  }
  if (lo < b) integrate(lo, b);  // beyond the end: extrapolated
  return total;
}

double HermiteHistory::Curvature(std::size_t piece, int i, double s) const {
  const double* p = PieceData(piece);
  const int n = dimension_;
  return QuarticSecondDerivative(s, t_end_[piece] - t_begin_[piece], p[i], p[n + i], p[2 * n + i], p[3 * n + i],
                                 p[4 * n + i]);
}

void HermiteHistory::KinksIn(double a, double b, int i, std::vector<Kink>& out) const {
  if (empty() || kinked_.empty() || t_begin_[kinked_.back()] < a) return;  // the usual case: no kink that late
  // The first kink at or after a: queries advance with time, so from the last answer, a step or two on.
  std::size_t k = std::min(kink_hint_, kinked_.size() - 1);
  if (k > 0 && t_begin_[kinked_[k - 1]] >= a) {
    auto starts_before = [this](std::size_t piece, double t) { return t_begin_[piece] < t; };
    k = static_cast<std::size_t>(std::lower_bound(kinked_.begin(), kinked_.end(), a, starts_before) - kinked_.begin());
  } else {
    while (k < kinked_.size() && t_begin_[kinked_[k]] < a) ++k;
  }
  kink_hint_ = k;
  for (auto it = kinked_.begin() + static_cast<std::ptrdiff_t>(k); it != kinked_.end() && t_begin_[*it] < b; ++it) {
    const double *left_value, *left_slope;  // the limits from the left at the knot
    if (*it > first_) {
      left_value = PieceData(*it - 1) + dimension_, left_slope = PieceData(*it - 1) + 3 * dimension_;
    } else if (*it == 0 && !origin_.empty()) {
      left_value = origin_.data(), left_slope = origin_.data() + dimension_;
    } else {
      continue;  // the oldest piece kept: its predecessor is gone
    }
    const double* right = PieceData(*it);
    const double slope_jump = right[2 * dimension_ + i] - left_slope[i], value_jump = right[i] - left_value[i];
    const double curvature_jump = *it > first_ ? Curvature(*it, i, 0.0) - Curvature(*it - 1, i, 1.0) : 0.0;
    if (slope_jump != 0 || value_jump != 0 || curvature_jump != 0)
      out.push_back({t_begin_[*it], slope_jump, value_jump, curvature_jump});
  }
}

void HermiteHistory::DiscardBefore(double t) {
  while (first_ + 1 < t_begin_.size() && t_end_[first_] < t) ++first_;
  if (first_ > 0) origin_.clear();  // the first piece is forgotten, and with it its knot
  // Compact when more than half of the storage is dead, so appends stay amortized O(1).
  if (first_ > 32 && first_ * 2 > t_begin_.size()) {
    const auto n = static_cast<std::ptrdiff_t>(first_);
    t_begin_.erase(t_begin_.begin(), t_begin_.begin() + n);
    t_end_.erase(t_end_.begin(), t_end_.begin() + n);
    data_.erase(data_.begin(), data_.begin() + n * kPerPiece * dimension_);
    kinked_.erase(kinked_.begin(), std::lower_bound(kinked_.begin(), kinked_.end(), first_));
    for (std::size_t& piece : kinked_) piece -= first_;
    kink_hint_ = 0;
    first_ = 0;
    hint_ = 0;
  }
}

}  // namespace drillwave::integration
