#pragma once
// Dense history of a vector-valued signal, built one accepted step at a time: a quartic piece per step from the
// values and derivatives at both ends and the value at the midpoint (the cubic Hermite interpolant plus a bubble
// s^2 (1-s)^2; with the midpoint of Dormand–Prince's continuous extension it reproduces that degree-4 extension). Pieces keep one-sided end values, so a jump or a kink at a
// breakpoint or event is stored exactly (the left piece holds the left limit, the right piece the right limit).
#include <functional>
#include <vector>

namespace drillwave::integration {

// The error of the quartic HermiteHistory stores for a piece of length h (ends x0 and x1, end derivatives d0 and d1,
// midpoint x_mid) against the exact values x_quarter at a quarter of the piece, in units of abs_tol + rel_tol
// max(|x0|, |x1|): the largest over the n components (> 1: the piece is not stored within the tolerance).
double QuarterPointError(int n, double h, const double* x0, const double* x1, const double* d0, const double* d1,
                         const double* x_mid, const double* x_quarter, double abs_tol, double rel_tol);

// Which one-sided limit to take when a query time falls on a piece boundary.
enum class Side { kLeft, kRight };

class HermiteHistory {
 public:
  // Values (and derivatives) before the first committed piece. Called with t < start of history.
  using Prehistory = std::function<void(double t, double* value, double* derivative)>;

  explicit HermiteHistory(int dimension);
  HermiteHistory(int dimension, Prehistory prehistory);

  int dimension() const { return dimension_; }
  bool empty() const { return first_ == t_begin_.size(); }
  double begin_time() const;  // start of the oldest piece still kept
  double end_time() const;    // end of the newest piece
  std::size_t num_pieces() const { return t_begin_.size() - first_; }

  // Appends the piece [t0, t1]; t0 must equal end_time() (up to rounding) unless the history is empty. restart: the
  // piece's start was computed anew (after an event or a breakpoint), so its curvature may jump there even where its
  // value and slope continue the last piece's; KinksIn looks at such a knot too.
  void Append(double t0, const double* x0, const double* d0, double t1, const double* x1, const double* d1,
              const double* x_mid, bool restart = false);

  // Component i at time t. Before the history: the prehistory; after its end: the last piece extrapolated (a
  // predictor for look-ups inside the step being taken, which the delay solver then iterates on).
  double Value(double t, int i, Side side = Side::kRight) const;
  double Derivative(double t, int i, Side side = Side::kRight) const;
  void Values(double t, double* out, Side side = Side::kRight) const;
  void Derivatives(double t, double* out, Side side = Side::kRight) const;
  void ValuesAndDerivatives(double t, double* value, double* derivative, Side side = Side::kRight) const;

  // Integral of component i squared over [a, b] (within the stored pieces): exact for the quartic pieces
  // (5-point Gauss–Legendre per piece). Used for the energy carried by waves in flight.
  double IntegrateSquare(int i, double a, double b) const;

  // A knot between two stored pieces where component i's value, slope or curvature jumps (which the pieces store
  // exactly, or, for the curvature, to the quartics' own accuracy): its time and the jumps, right limit minus left.
  struct Kink {
    double time_s;
    double slope_jump;
    double value_jump;
    double curvature_jump;  // 0 against the prehistory (the chains' prehistories are steady)
  };
  // Appends to out the knots in [a, b) where component i's slope or value jumps by more than rounding (1e-12
  // relative), or that start a restarted piece: between two pieces, and between the prehistory and the first piece
  // while that is kept (a start that does not continue the prehistory). Not the start of an oldest piece kept whose
  // predecessor is gone. Cheap: Append indexes such knots, and most knots are none.
  void KinksIn(double a, double b, int i, std::vector<Kink>& out) const;

  // Forgets pieces that end before t (for constant delays: t = now - largest delay).
  void DiscardBefore(double t);

 private:
  struct Location {
    std::size_t piece;  // index into the arrays; kPrehistory if before the history
    double s;           // normalized position in the piece (0..1, may exceed 1 when extrapolating)
  };
  static constexpr int kPerPiece = 5;
  static constexpr std::size_t kPrehistory = static_cast<std::size_t>(-1);
  Location Locate(double t, Side side) const;
  double Curvature(std::size_t piece, int i, double s) const;  // component i's second derivative at s in [0, 1]
  const double* PieceData(std::size_t piece) const { return &data_[piece * kPerPiece * dimension_]; }

  int dimension_;
  Prehistory prehistory_;
  std::size_t first_ = 0;       // pieces before this index are discarded (compacted lazily)
  std::vector<double> t_begin_;
  std::vector<double> t_end_;
  std::vector<double> data_;    // per piece: x0[dim], x1[dim], d0[dim], d1[dim], bubble[dim]
  std::vector<std::size_t> kinked_;  // pieces (indices as above, ascending) whose start differs from the last end
  // The prehistory's value and slope at the first piece's start, while that piece is kept (its knot can be a kink).
  std::vector<double> origin_;  // value[dim], slope[dim]; empty once the first piece is forgotten
  mutable std::size_t kink_hint_ = 0;  // index into kinked_ of the last KinksIn answer (a cache, like hint_)
  mutable std::vector<double> scratch_value_, scratch_deriv_;
  mutable std::size_t hint_ = 0;  // piece of the last look-up (a cache; makes a history unsafe to share across threads)
};

}  // namespace drillwave::integration
