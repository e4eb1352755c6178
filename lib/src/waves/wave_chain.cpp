#include "drillwave/waves/wave_chain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace drillwave::waves {
namespace {

// Sum of Z (2 w_in) over the two pieces at an internal node (as 2 Z (a + b) for equal impedances: a uniform
// string keeps the rounding it had before pieces could differ).
double Incoming(double z_above, double above, double z_below, double below) {
  return z_above == z_below ? 2 * z_above * (above + below) : 2 * (z_above * above + z_below * below);
}

// A kink matters to a piece of length h when the quartic across it would miss by more than the tolerance unit: by
// up to 0.07 |slope jump| h at its quarter point (a kink at 0.4 h), and by up to 0.0057 |curvature jump| h^2 for a
// jump of the second derivative (an event where the bit's acceleration is continuous but its rate is not). Smaller
// ones (the weak reflections at the damped nodes) are left to the pieces. A jump matters above a tenth of the unit.
bool Matters(const integration::HermiteHistory::Kink& k, double h, double scale) {
  return 0.08 * std::abs(k.slope_jump) * h > scale || 0.006 * std::abs(k.curvature_jump) * h * h > scale ||
         std::abs(k.value_jump) > 0.1 * scale;
}

}  // namespace

bool PassedWith(double kink_time, double t) { return kink_time <= t + 1e-9 * std::max(1.0, std::abs(t)); }

double ChainSpec::ShortestPiece() const { return *std::min_element(tau.begin(), tau.end()); }
double ChainSpec::LongestPiece() const { return *std::max_element(tau.begin(), tau.end()); }
double ChainSpec::travel_time() const {
  double total = 0;
  for (double t : tau) total += t;
  return total;
}

// Steady motion: S_{j-1} = S_j + c_j v - load_j (+ the Coulomb level against forward motion), from the bit up.
WaveChain::WaveChain(const ChainSpec& spec, double v, double bit_force) : spec_(spec), m_(spec.pieces()) {
  const ChainSpec& ch = spec_;
  std::vector<double> initial(2 * (m_ + 1), 0.0);  // by node, as Outgoing lays the waves out
  double s = bit_force + ch.damping[m_] * v - ch.load[m_] + ch.coulomb[m_];
  for (int j = m_ - 1; j >= 0; --j) {
    initial[NodeBlock(j) + 1] = 0.5 * (v + s / ch.z[j]);  // D_j: D - U = S / Z, D + U = v
    initial[NodeBlock(j + 1)] = 0.5 * (v - s / ch.z[j]);  // U_j
    if (j > 0) s += ch.damping[j] * v - ch.load[j] + ch.coulomb[j];
  }
  steady_top_force_ = s + ch.damping[0] * v - ch.load[0];
  // Kelvin-Voigt: the internal nodes' tridiagonal system, held by side friction where there is some.
  if (ch.kelvin_voigt()) {
    held_friction_ = std::any_of(ch.coulomb.begin(), ch.coulomb.end(), [](double c) { return c > 0; });
    for (int j = 1; j < m_; ++j) {
      held_.diagonal.push_back(ch.z[j - 1] + ch.z[j] + ch.damping[j] + ch.kv[j - 1] + ch.kv[j]);
      held_.friction.push_back(ch.coulomb[j]);
      if (j + 1 < m_) held_.coupling.push_back(ch.kv[j]);
    }
    if (!held_friction_) held_.FactorLinear();
  }
  end_slopes_ = FindEndSlopes();
  node_waves_.reserve(m_ + 1);
  for (int j = 0; j <= m_; ++j) {
    const double up = initial[NodeBlock(j)], down = initial[NodeBlock(j) + 1];
    node_waves_.emplace_back(2, [up, down](double, double* value, double* rate) {
      value[0] = up, value[1] = down;
      rate[0] = rate[1] = 0.0;
    });
  }
}

void WaveChain::CloseEnds(const EndClosure* top, const EndClosure* bit) {
  if ((top || bit) && spec_.kelvin_voigt())
    throw std::logic_error("WaveChain::CloseEnds: with Kelvin-Voigt dashpots the caller solves the ends' speeds");
  top_closure_ = top, bit_closure_ = bit;
}

// Each end feels -(Z + c) v from its own speed; a Kelvin-Voigt dashpot kv pulls it towards its neighbour, whose speed
// (a massless node) moves with both ends' through the dashpot chain: dv_inner / dv_end = H^-1 e kv.
WaveChain::EndSlopes WaveChain::FindEndSlopes() const {
  const ChainSpec& ch = spec_;
  EndSlopes s{-ch.z[0] - ch.damping[0], 0.0, 0.0, -ch.z[m_ - 1] - ch.damping[m_]};
  if (!ch.kelvin_voigt()) return s;
  if (held_friction_) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan};
  }
  const double kv_top = ch.kv[0], kv_bit = ch.kv[m_ - 1];
  s.top_top -= kv_top, s.bit_bit -= kv_bit;
  if (m_ == 1) {  // one piece: its dashpot ties the ends directly
    s.top_bit = kv_top, s.bit_top = kv_bit;
    return s;
  }
  const int n = m_ - 1;
  std::vector<double> unit(n, 0.0), from_top, from_bit;
  unit[0] = kv_top;
  held_.SolveLinear(unit, from_top);
  unit.assign(n, 0.0), unit[n - 1] = kv_bit;
  held_.SolveLinear(unit, from_bit);
  s.top_top += kv_top * from_top[0], s.top_bit = kv_top * from_bit[0];
  s.bit_top = kv_bit * from_top[n - 1], s.bit_bit += kv_bit * from_bit[n - 1];
  return s;
}

ChainEnds WaveChain::EndForceRates(double t, Side side, ChainEnds speeds, ChainEnds rates) const {
  const ChainSpec& ch = spec_;
  double in_top, in_bit, pull_top = 0, pull_bit = 0;
  if (ch.kelvin_voigt()) {
    arriving_.resize(2 * m_), arriving_rate_.resize(2 * m_), speeds_.resize(m_ + 1), speed_rates_.resize(m_ + 1);
    Arrivals(t, side, arriving_.data(), arriving_rate_.data());
    NodeSpeeds(arriving_.data(), speeds.top, speeds.bit, speeds_.data());  // which nodes side friction holds
    NodeRates(arriving_rate_.data(), speeds_.data(), rates.top, rates.bit, speed_rates_.data());
    in_top = arriving_rate_[1], in_bit = arriving_rate_[2 * (m_ - 1)];
    pull_top = ch.kv[0] * (speed_rates_[1] - rates.top), pull_bit = ch.kv[m_ - 1] * (speed_rates_[m_ - 1] - rates.bit);
  } else {
    in_top = NodeHistory(1).Derivative(t - ch.tau[0], 0, side);
    in_bit = NodeHistory(m_ - 1).Derivative(t - ch.tau[m_ - 1], 1, side);
  }
  return {ch.z[0] * (2 * in_top - rates.top) - ch.damping[0] * rates.top + pull_top,
          ch.z[m_ - 1] * (2 * in_bit - rates.bit) - ch.damping[m_] * rates.bit + pull_bit};
}

void WaveChain::NodeSpeedsAt(double t, Side side, ChainEnds speeds, std::vector<double>& v) const {
  arriving_.resize(2 * m_);
  v.resize(m_ + 1);
  Arrivals(t, side, arriving_.data(), nullptr);
  NodeSpeeds(arriving_.data(), speeds.top, speeds.bit, v.data());
}

double WaveChain::WaveEnergy(double t) const {
  double e = 0;
  for (int k = 0; k < m_; ++k) {
    const double a = t - spec_.tau[k];
    e += spec_.z[k] * (NodeHistory(k).IntegrateSquare(1, a, t) + NodeHistory(k + 1).IntegrateSquare(0, a, t));
  }
  return e;
}

// Node j's U_{j-1} arrives at node j-1 as in[2j - 1] and its D_j at node j+1 as in[2j]: component 2k is down-going
// at the bottom of piece k, 2k + 1 up-going at its top.
double WaveChain::Arrival(int j, double t, Side side, bool from_above) const {
  const std::vector<double>& tau = spec_.tau;
  return from_above ? NodeHistory(j - 1).Value(t - tau[j - 1], 1, side)  // D_{j-1}, sent by node j - 1
                    : NodeHistory(j + 1).Value(t - tau[j], 0, side);     // U_j, sent by node j + 1
}

void WaveChain::Arrivals(double t, Side side, double* in, double* rate) const {
  const std::vector<double>& tau = spec_.tau;
  for (int j = 0; j <= m_; ++j) {
    const integration::HermiteHistory& sent = NodeHistory(j);
    if (j > 0 && j < m_ && tau[j - 1] == tau[j]) {  // both sent at the same time: one look-up
      double two[2], two_rates[2];
      if (rate) {
        sent.ValuesAndDerivatives(t - tau[j], two, two_rates, side);
        rate[2 * j - 1] = two_rates[0], rate[2 * j] = two_rates[1];
      } else {
        sent.Values(t - tau[j], two, side);
      }
      in[2 * j - 1] = two[0], in[2 * j] = two[1];
      continue;
    }
    if (j > 0) {
      in[2 * j - 1] = sent.Value(t - tau[j - 1], 0, side);
      if (rate) rate[2 * j - 1] = sent.Derivative(t - tau[j - 1], 0, side);
    }
    if (j < m_) {
      in[2 * j] = sent.Value(t - tau[j], 1, side);
      if (rate) rate[2 * j] = sent.Derivative(t - tau[j], 1, side);
    }
  }
}

void WaveChain::NodeSpeeds(const double* in, double top, double bit, double* v) const {
  v[0] = top, v[m_] = bit;
  if (held_.size()) {
    SolveHeldNodes(in, top, bit, nullptr, v);
    return;
  }
  for (int j = 1; j < m_; ++j) v[j] = InternalNodeSpeed(j, in[2 * (j - 1)], in[2 * j + 1]);
}

// A massless node j with Coulomb friction T_f, wave a arriving from above and b from below: 0 in
// (Z_a + Z_b + c) v - q + T_f sign(v), q = 2 Z_a a + 2 Z_b b + load, solved in closed form: the node stands still
// while |q| <= T_f and slides with the excess otherwise.
double WaveChain::InternalNodeSpeed(int j, double a, double b) const {
  const ChainSpec& ch = spec_;
  const double q = Incoming(ch.z[j - 1], a, ch.z[j], b) + ch.load[j];
  const double excess = std::max(std::abs(q) - ch.coulomb[j], 0.0);
  return std::copysign(excess, q) / (ch.z[j - 1] + ch.z[j] + ch.damping[j]);
}

// Its rate from the arriving waves' rates (a node held by Coulomb friction stays).
double WaveChain::InternalNodeRate(int j, double rate_a, double rate_b, double v) const {
  const ChainSpec& ch = spec_;
  return v != 0 || ch.coulomb[j] == 0
             ? Incoming(ch.z[j - 1], rate_a, ch.z[j], rate_b) / (ch.z[j - 1] + ch.z[j] + ch.damping[j])
             : 0.0;
}

void WaveChain::NodeRates(const double* in_rate, const double* v, double top, double bit, double* dv) const {
  dv[0] = top, dv[m_] = bit;
  if (held_.size()) {
    SolveHeldNodes(in_rate, top, bit, v, dv);
    return;
  }
  for (int j = 1; j < m_; ++j) dv[j] = InternalNodeRate(j, in_rate[2 * (j - 1)], in_rate[2 * j + 1], v[j]);
}

// With Kelvin-Voigt dashpots kv_k across the pieces, node j (1..m-1) balances
//   (Z_{j-1} + Z_j + c_j + kv_{j-1} + kv_j) v_j - kv_{j-1} v_{j-1} - kv_j v_{j+1} = 2 Z_{j-1} a + 2 Z_j b + load_j,
// a tridiagonal system in the internal speeds (its rates: the same matrix, without the loads), solved by HeldNodes:
// directly without side friction; with it (Coulomb friction at the nodes) speeds (v == nullptr) are warm-started from
// the last solution, and for the rates the nodes at rest in v are held and the others' rates solved.
void WaveChain::SolveHeldNodes(const double* in, double top, double bit, const double* v, double* out) const {
  const ChainSpec& ch = spec_;
  const int n = m_ - 1;
  held_rhs_.resize(n);
  for (int j = 1; j < m_; ++j)
    held_rhs_[j - 1] = Incoming(ch.z[j - 1], in[2 * (j - 1)], ch.z[j], in[2 * j + 1]) + (v ? 0.0 : ch.load[j]);
  held_rhs_[0] += ch.kv[0] * top;
  held_rhs_[n - 1] += ch.kv[m_ - 1] * bit;
  if (!held_friction_) {
    held_.SolveLinear(held_rhs_, held_out_);
  } else if (!v) {
    held_.Solve(held_rhs_, held_out_, held_state_);
  } else {
    held_rate_state_.resize(n);
    for (int j = 1; j < m_; ++j) held_rate_state_[j - 1] = v[j] == 0 && ch.coulomb[j] > 0 ? 0 : 1;
    held_.Rates(held_rhs_, held_rate_state_, held_out_);
  }
  std::copy(held_out_.begin(), held_out_.end(), out + 1);
}

ChainEnds WaveChain::EndForces(double t, Side side, ChainEnds speeds) const {
  const ChainSpec& ch = spec_;
  const double top = speeds.top, bit = speeds.bit;
  double in_top, in_bit, pull_top = 0, pull_bit = 0;  // pull: the Kelvin-Voigt dashpots of the end pieces
  if (ch.kelvin_voigt()) {  // the dashpots tie the end nodes to the massless nodes next to them: solve them all
    arriving_.resize(2 * m_), speeds_.resize(m_ + 1);
    Arrivals(t, side, arriving_.data(), nullptr);
    NodeSpeeds(arriving_.data(), top, bit, speeds_.data());
    in_top = arriving_[1], in_bit = arriving_[2 * (m_ - 1)];
    pull_top = ch.kv[0] * (speeds_[1] - top), pull_bit = ch.kv[m_ - 1] * (speeds_[m_ - 1] - bit);
  } else {
    in_top = Arrival(0, t, side, false), in_bit = Arrival(m_, t, side, true);
  }
  return {EndForce(0, in_top, top, pull_top), EndForce(m_, in_bit, bit, pull_bit)};
}

// The string's force on end node `end` (0 or m) turning at v with the wave `in` arriving: Z (2 in - v) of its piece,
// its own damper and load, and `pull`, its piece's Kelvin-Voigt dashpot.
double WaveChain::EndForce(int end, double in, double v, double pull) const {
  const ChainSpec& ch = spec_;
  return ch.z[end == 0 ? 0 : m_ - 1] * (2 * in - v) - ch.damping[end] * v + ch.load[end] + pull;
}

double WaveChain::TopForce(double t, Side side, ChainEnds speeds) const {
  if (spec_.kelvin_voigt()) return EndForces(t, side, speeds).top;
  return EndForce(0, Arrival(0, t, side, false), speeds.top, 0.0);
}

WaveChain::Wave WaveChain::TopArrival(double t, Side side) const {
  const double sent = t - spec_.tau[0];  // U_0, sent by node 1
  return {NodeHistory(1).Value(sent, 0, side), NodeHistory(1).Derivative(sent, 0, side)};
}

double WaveChain::BitForce(double t, Side side, ChainEnds speeds) const {
  if (spec_.kelvin_voigt()) return EndForces(t, side, speeds).bit;
  return EndForce(m_, Arrival(m_, t, side, true), speeds.bit, 0.0);
}

// Waves leaving every node at time t (and their rates when rate != nullptr), laid out by node (NodeBlock).
void WaveChain::Outgoing(double t, ChainEnds speeds, const ChainEnds* rates, Side side, double* out,
                         double* rate) const {
  arriving_.resize(2 * m_), arriving_rate_.resize(2 * m_), speeds_.resize(m_ + 1), speed_rates_.resize(m_ + 1);
  Arrivals(t, side, arriving_.data(), rate ? arriving_rate_.data() : nullptr);
  const ChainSpec& ch = spec_;
  const double in_top = arriving_[1], in_bit = arriving_[2 * (m_ - 1)];  // the waves arriving at the ends
  if (top_closure_) speeds.top = top_closure_->Speed(t, side, 2 * ch.z[0] * in_top + ch.load[0]);
  if (bit_closure_) speeds.bit = bit_closure_->Speed(t, side, 2 * ch.z[m_ - 1] * in_bit + ch.load[m_]);
  NodeSpeeds(arriving_.data(), speeds.top, speeds.bit, speeds_.data());
  for (int j = 0; j <= m_; ++j) {
    const int b = NodeBlock(j);
    out[b] = j > 0 ? speeds_[j] - arriving_[2 * (j - 1)] : 0.0;     // up-going into piece j-1
    out[b + 1] = j < m_ ? speeds_[j] - arriving_[2 * j + 1] : 0.0;  // down-going into piece j
  }
  if (!rate) return;
  ChainEnds end_rates = *rates;
  if (top_closure_) end_rates.top = top_closure_->Rate(t, side, speeds.top, 2 * ch.z[0] * arriving_rate_[1]);
  if (bit_closure_)
    end_rates.bit = bit_closure_->Rate(t, side, speeds.bit, 2 * ch.z[m_ - 1] * arriving_rate_[2 * (m_ - 1)]);
  rates = &end_rates;
  NodeRates(arriving_rate_.data(), speeds_.data(), rates->top, rates->bit, speed_rates_.data());
  for (int j = 0; j <= m_; ++j) {
    const int b = NodeBlock(j);
    rate[b] = j > 0 ? speed_rates_[j] - arriving_rate_[2 * (j - 1)] : 0.0;
    rate[b + 1] = j < m_ ? speed_rates_[j] - arriving_rate_[2 * j + 1] : 0.0;
  }
}

// The waves leaving every node over the step, and the error of the quartic the history stores for them (ends, end
// rates, midpoint) against their exact value at a quarter of the step: a wave buffer is history too, and its
// interpolation error is invisible to the stepper. A kink that arrives at an internal node within the step would
// fail that check for any piece across it, and cost rejected steps at every node it passes; the node's waves are
// then stored in parts split at the kink, each part exact to the check (SplitNodeWaves).
double WaveChain::Prepare(const StepEnds& step, double abs_tol, double rel_tol) {
  const int k = 2 * (m_ + 1);
  out0_.resize(k), out1_.resize(k), outm_.resize(k), outq_.resize(k), d0_.resize(k), d1_.resize(k);
  // Without an event or breakpoint in between, the start of this step is the end of the last one.
  prepared_restart_ = ReadsStart(step.t0);
  if (prepared_restart_)
    Outgoing(step.t0, step.speed0, &step.rate0, Side::kRight, out0_.data(), d0_.data());
  // In time order, so that each history's look-ups walk forward from the last one.
  const double h = step.t1 - step.t0;
  Outgoing(step.t0 + 0.25 * h, step.speed_quarter, nullptr, Side::kLeft, outq_.data(), nullptr);
  Outgoing(0.5 * (step.t0 + step.t1), step.speed_mid, nullptr, Side::kLeft, outm_.data(), nullptr);
  Outgoing(step.t1, step.speed1, &step.rate1, Side::kLeft, out1_.data(), d1_.data());
  num_splits_ = 0;
  double worst = 0;
  // Kelvin-Voigt dashpots tie every node to its neighbours: its nodes' waves are not split (a kink then costs
  // rejected steps as before).
  const bool splits = !spec_.kelvin_voigt();
  for (int j = 0; j <= m_; ++j) {
    const int b = NodeBlock(j);
    if (splits && j > 0 && j < m_) {
      const double scale = WaveScale(b, abs_tol, rel_tol);
      split_times_.clear();
      // A knot that arrives on the step's start: the waves kept from the last step's end are its left limits.
      if (ArrivingKinks(j, step.t0, step.t1, scale, split_times_) && !prepared_restart_)
        NodeWaves(j, step.t0, Side::kRight, &out0_[b], &d0_[b]);
      if (!split_times_.empty()) {
        worst = std::max(worst, SplitNodeWaves(j, step.t0, step.t1, abs_tol, rel_tol));
        continue;
      }
    }
    worst = std::max(worst, integration::QuarterPointError(2, h, &out0_[b], &out1_[b], &d0_[b], &d1_[b], &outm_[b],
                                                           &outq_[b], abs_tol, rel_tol));
  }
  prepared_scale_ = {abs_tol, rel_tol};
  return worst;
}

void WaveChain::Commit(double t0, double t1, double read_back, std::vector<double>& end_kinks) {
  std::size_t split = 0;
  for (int j = 0; j <= m_; ++j) {
    integration::HermiteHistory& history = NodeHistory(j);
    if (split < num_splits_ && splits_[split].node == j) {
      const SplitWaves& s = splits_[split++];
      for (std::size_t q = 0; q + 1 < s.time.size(); ++q)
        history.Append(s.time[q], &s.value_right[2 * q], &s.rate_right[2 * q], s.time[q + 1], &s.value_left[2 * q + 2],
                       &s.rate_left[2 * q + 2], &s.mid[2 * q], q > 0);  // a knot arrived there
    } else {
      const int b = NodeBlock(j);
      // An end's waves depend on the state, whose curvature may jump at a restart (an event); an inner node's do only
      // where a knot arrives (split there).
      history.Append(t0, &out0_[b], &d0_[b], t1, &out1_[b], &d1_[b], &outm_[b], prepared_restart_ && (j == 0 || j == m_));
    }
  }
  out0_.swap(out1_);
  d0_.swap(d1_);
  start_is_last_end_ = true;
  last_commit_end_ = t1;
  for (auto& w : node_waves_) w.DiscardBefore(t1 - read_back);
  // The kinks just stored next to the top and the bit reach them one piece later; with dashpots, those stored at any
  // node reach its neighbours, and through the dashpots the ends, one piece later.
  if (spec_.kelvin_voigt()) {
    for (int j = 0; j <= m_; ++j) {
      if (j > 0) EndKinks(NodeHistory(j), 0, spec_.tau[j - 1], t0, t1, NodeBlock(j), end_kinks);
      if (j < m_) EndKinks(NodeHistory(j), 1, spec_.tau[j], t0, t1, NodeBlock(j) + 1, end_kinks);
    }
    return;
  }
  EndKinks(NodeHistory(1), 0, spec_.tau[0], t0, t1, NodeBlock(1), end_kinks);                     // up, to the top
  EndKinks(NodeHistory(m_ - 1), 1, spec_.tau[m_ - 1], t0, t1, NodeBlock(m_ - 1) + 1, end_kinks);  // down, to the bit
}

// The tolerance unit of the waves of the prepared node block b.
double WaveChain::WaveScale(int b, double abs_tol, double rel_tol) const {
  return abs_tol + rel_tol * std::max({std::abs(out0_[b]), std::abs(out0_[b + 1]), std::abs(out1_[b]),
                                       std::abs(out1_[b + 1])});
}

// Times within (t0, t1) at which knots that matter (jumps, kinks, curvature jumps) arrive at internal node j, sorted,
// without repeats; returns whether one arrives on t0 itself (within rounding).
bool WaveChain::ArrivingKinks(int j, double t0, double t1, double scale, std::vector<double>& times) const {
  const std::vector<double>& tau = spec_.tau;
  const double h = t1 - t0, margin = 1e-9 * h;
  kinks_.clear();
  NodeHistory(j - 1).KinksIn(t0 - margin - tau[j - 1], t1 - tau[j - 1], 1, kinks_);
  for (auto& k : kinks_) k.time_s += tau[j - 1];
  const std::size_t from_above = kinks_.size();
  NodeHistory(j + 1).KinksIn(t0 - margin - tau[j], t1 - tau[j], 0, kinks_);
  for (std::size_t i = from_above; i < kinks_.size(); ++i) kinks_[i].time_s += tau[j];
  bool at_start = false;
  for (const auto& k : kinks_) {
    if (k.time_s <= t0 + margin) at_start = at_start || k.time_s >= t0 - margin;
    else if (k.time_s < t1 - margin && Matters(k, h, scale)) times.push_back(k.time_s);
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end(), [&](double a, double b) { return b - a <= margin; }),
              times.end());
  return at_start;
}

// The two waves internal node j sends at time t (and their rates): algebraic in the waves arriving.
void WaveChain::NodeWaves(int j, double t, Side side, double* out, double* rate) const {
  const double sent_above = t - spec_.tau[j - 1], sent_below = t - spec_.tau[j];
  const double a = NodeHistory(j - 1).Value(sent_above, 1, side), b = NodeHistory(j + 1).Value(sent_below, 0, side);
  const double v = InternalNodeSpeed(j, a, b);
  out[0] = v - a, out[1] = v - b;
  if (!rate) return;
  const double ra = NodeHistory(j - 1).Derivative(sent_above, 1, side);
  const double rb = NodeHistory(j + 1).Derivative(sent_below, 0, side);
  const double dv = InternalNodeRate(j, ra, rb, v);
  rate[0] = dv - ra, rate[1] = dv - rb;
}

// Node j's waves over the prepared step in parts split at split_times_ (splits_ keeps them for Commit), and the
// largest quarter-point error of the parts.
double WaveChain::SplitNodeWaves(int j, double t0, double t1, double abs_tol, double rel_tol) {
  const int b = NodeBlock(j);
  if (num_splits_ == splits_.size()) splits_.emplace_back();
  SplitWaves& s = splits_[num_splits_++];  // reused, with its storage
  s.node = j;
  s.time.assign(1, t0);
  s.time.insert(s.time.end(), split_times_.begin(), split_times_.end());
  s.time.push_back(t1);
  const std::size_t parts = s.time.size() - 1;
  for (auto* v : {&s.value_left, &s.value_right, &s.rate_left, &s.rate_right}) v->resize(2 * (parts + 1));
  s.mid.resize(2 * parts);
  std::copy_n(&out0_[b], 2, &s.value_right[0]), std::copy_n(&d0_[b], 2, &s.rate_right[0]);
  std::copy_n(&out1_[b], 2, &s.value_left[2 * parts]), std::copy_n(&d1_[b], 2, &s.rate_left[2 * parts]);
  for (std::size_t q = 1; q < parts; ++q) {  // both limits: a jump may arrive there
    NodeWaves(j, s.time[q], Side::kLeft, &s.value_left[2 * q], &s.rate_left[2 * q]);
    NodeWaves(j, s.time[q], Side::kRight, &s.value_right[2 * q], &s.rate_right[2 * q]);
  }
  double worst = 0, quarter[2];
  for (std::size_t q = 0; q < parts; ++q) {
    const double start = s.time[q], h = s.time[q + 1] - start;
    NodeWaves(j, start + 0.5 * h, Side::kLeft, &s.mid[2 * q], nullptr);
    NodeWaves(j, start + 0.25 * h, Side::kLeft, quarter, nullptr);
    worst = std::max(worst, integration::QuarterPointError(2, h, &s.value_right[2 * q], &s.value_left[2 * q + 2],
                                                           &s.rate_right[2 * q], &s.rate_left[2 * q + 2],
                                                           &s.mid[2 * q], quarter, abs_tol, rel_tol));
  }
  return worst;
}

// Kinks of component comp of an end's neighbour stored with this step (the knot at its start included) reach the
// end tau later. b: the component's place in the prepared waves (for its scale).
void WaveChain::EndKinks(const integration::HermiteHistory& sender, int comp, double tau, double t0, double t1, int b,
                         std::vector<double>& end_kinks) {
  kinks_.clear();
  sender.KinksIn(t0, t1, comp, kinks_);
  const double scale = prepared_scale_[0] + prepared_scale_[1] * std::abs(out0_[b]);  // out0_: now this step's end
  for (const auto& k : kinks_)
    if (Matters(k, t1 - t0, scale)) end_kinks.push_back(k.time_s + tau);
}

}  // namespace drillwave::waves
