#pragma once
/// @file
/// The largest travel of every deck corner normal to its end line over a run [docs/theory.md §2,
/// deck geometry]: the quantity model::CornerTravelAt gives at one instant, maximised over time
/// by the integrators beside the maxima of |q_i|, at the same exactness.
///
/// With n_e = (cos a, -sin a) the unit normal of the end lines, the travel of corner P_k of a deck
/// at (x, y, theta) is
///
///     f_k = n_e . (x, y) + (cos theta - 1) A_k + sin theta B_k,
///     A_k = n_e . P_k,  B_k = n_e . (-P_k,y, P_k,x),
///
/// and its rate df_k/dt = n_e . (u_x, u_y) + u_theta (-sin theta A_k + cos theta B_k). The
/// corners come in opposite pairs (P_3 = -P_1, P_4 = -P_2), so f_3 = T - g_1 and f_4 = T - g_2 with
/// T = n_e . (x, y), g_j = (cos theta - 1) A_j + sin theta B_j; the travel max_k |f_k| is
/// |T| + max(|g_1|, |g_2|). Its largest value over a step lies at the step's ends or where a
/// corner's rate df_k/dt changes sign inside it; the integrators find that instant by Brent's
/// method on df_k/dt over their dense output, exactly as they find the peaks of |q_i|.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include "solver/dynamics/root_finding.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics {

/// The geometry of every deck's corner travel, and the travel's running maximum over a run.
/// Built once per run (it allocates there); Update and Scan allocate nothing.
class CornerTravelTracker {
 public:
  /// The decks of `model`: deck i occupies DOFs 3 i .. 3 i + 2 (x, y, theta).
  explicit CornerTravelTracker(const model::Model& model) { Assign(model); }
  /// No decks (Assign gives it some).
  CornerTravelTracker() = default;
  /// Tracks the decks of `model` instead, in the storage it has (no allocation for as many decks).
  void Assign(const model::Model& model);

  /// Number of decks tracked.
  int decks() const { return static_cast<int>(decks_.size()); }

  /// Sets the running maxima to the travels at q (m), one per deck, into `max_travel_m`.
  void Start(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& max_travel_m);

  /// Raises `max_travel_m` to the travels at q (m): the grid points of a time-stepping run.
  void Update(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& max_travel_m) const;

  /// Raises `max_travel_m` to the largest travel of each deck over [t0, t1]: at t1, and, for every
  /// corner whose rate changes sign inside the step and whose peak could exceed the running
  /// maximum (bound: the larger end value plus (t1 - t0) / 2 times the smaller end rate, twice
  /// the rise of a linear rate), at the root of its rate located by Brent's method to
  /// `time_tolerance_s`.
  /// @param component_at (t, i) -> entry i of the state (q, u) (n_dof + n_dof entries) at t in
  /// [t0, t1], from the step's dense output; where (t, const int (&i)[4], double (&out)[4])
  /// is a call too, it reads a corner's rate's four entries at once (the same values).
  template <class ComponentAt>
  void Scan(double t0, const Eigen::Ref<const Eigen::VectorXd>& q0,
            const Eigen::Ref<const Eigen::VectorXd>& u0, double t1,
            const Eigen::Ref<const Eigen::VectorXd>& q1,
            const Eigen::Ref<const Eigen::VectorXd>& u1, double time_tolerance_s,
            ComponentAt&& component_at, Eigen::VectorXd& max_travel_m) {
    using Map = Eigen::Map<const Eigen::VectorXd>;
    Scan(t0, Map(q0.data(), q0.size()), Map(u0.data(), u0.size()), t1, Map(q1.data(), q1.size()),
         Map(u1.data(), u1.size()), time_tolerance_s, component_at, max_travel_m,
         [](int, double, double, double, double, double, double, double, double) {
           return std::numeric_limits<double>::infinity();
         });
  }

  /// Scan, with a bound that can spare a corner's root search: travel_bound(b, n_x, n_y, r, f0,
  /// r0, f1, r1, h) is an upper bound of |f| over [t0, t1] (h = t1 - t0, s) for a corner of the
  /// deck at DOF b with end-line normal (n_x, n_y) and radius at most r (m), travel f0, f1 (m)
  /// and rate r0, r1 (m/s) at the step's ends (+inf: none); a corner whose bound is below the
  /// running maximum is not searched (the search could not raise it) [docs/theory.md §3.20].
  /// The ends are plain maps of the state's storage: nothing to build or destroy per step.
  /// Inline: the reach test of every deck (most steps end there), the rest out of line.
  template <class ComponentAt, class TravelBound>
  void Scan(double t0, const Eigen::Map<const Eigen::VectorXd>& q0,
            const Eigen::Map<const Eigen::VectorXd>& u0, double t1,
            const Eigen::Map<const Eigen::VectorXd>& q1,
            const Eigen::Map<const Eigen::VectorXd>& u1, double time_tolerance_s,
            ComponentAt&& component_at, Eigen::VectorXd& max_travel_m, TravelBound&& travel_bound) {
    const double* x0 = q0.data();
    const double* v0 = u0.data();
    const double* x1 = q1.data();
    const double* v1 = u1.data();
    const int decks = this->decks();
    for (int d = 0; d < decks; ++d) {
      if (!MayReach(d, x0, v0, x1, v1, t1 - t0, max_travel_m[d])) continue;
      ScanDeck(d, t0, q0, u0, t1, q1, u1, time_tolerance_s, component_at, max_travel_m[d],
               travel_bound);
    }
  }

  /// Whether deck d's corner travel may reach `best` (m) over a step of h_s (s) with the
  /// positions x and velocities v (n_dof each) at its ends: false when neither end nor the
  /// interior peak that Scan's root search could find can reach it, so that Scan evaluates no
  /// corner of the deck. Scan's test; inline. Each end's (reach, speed) in the two lanes of one
  /// operand (EndReach's lanes, the same bits as its scalar terms), then MayReach's lanes (the
  /// same answer).
  bool MayReach(int d, const double* x0, const double* v0, const double* x1, const double* v1,
                double h_s, double best) const {
    const ReachConstants c = reach_constants(d);
    const int b = 3 * d;
    const ReachLanes s0[3] = {{x0[b], v0[b]}, {x0[b + 1], v0[b + 1]}, {x0[b + 2], v0[b + 2]}};
    const ReachLanes s1[3] = {{x1[b], v1[b]}, {x1[b + 1], v1[b + 1]}, {x1[b + 2], v1[b + 2]}};
    return MayReach(EndReach(c, s0), EndReach(c, s1), h_s, best);
  }

  /// MayReach's terms of one end of a step for deck d: the reach |n_e . (x, y)| + r |theta| (m)
  /// and the speed, the same of the velocities (m/s), from the positions x and velocities v
  /// (n_dof each). A step's end gives the next step's start the same terms.
  void EndReach(int d, const double* x, const double* v, double& reach, double& speed) const {
    const Deck& deck = decks_[static_cast<std::size_t>(d)];
    const int b = 3 * d;
    // A corner moves at most |theta| r from the translation's share (|(R(theta) - E) P| <=
    // |theta| |P| <= |theta| r) and at most |u_theta| r faster.
    const double r = deck.radius;
    reach = std::abs(deck.nx * x[b] + deck.ny * x[b + 1]) + r * std::abs(x[b + 2]);
    speed = std::abs(deck.nx * v[b] + deck.ny * v[b + 1]) + r * std::abs(v[b + 2]);
  }

  /// A deck's coordinate and its velocity side by side in two lanes, (q_i, u_i): each operation
  /// on it is the IEEE operation on each lane.
  using ReachLanes = double __attribute__((vector_size(16)));
  /// EndReach's constants of one deck, each in both lanes: the end-line normal (n_x, n_y) and
  /// the radius r (m).
  struct ReachConstants {
    ReachLanes nx, ny, r;
  };
  /// Deck d's EndReach constants.
  ReachConstants reach_constants(int d) const {
    const Deck& deck = decks_[static_cast<std::size_t>(d)];
    ReachConstants c;
    c.nx = ReachLanes{deck.nx, deck.nx};
    c.ny = ReachLanes{deck.ny, deck.ny};
    c.r = ReachLanes{deck.radius, deck.radius};
    return c;
  }
  /// EndReach with the deck's (x, u_x), (y, u_y), (theta, u_theta) in x[0], x[1], x[2]: (reach,
  /// speed) in the two lanes, each lane EndReach's operations in its order (a magnitude by
  /// clearing the sign bit, as std::abs does), so the same bits.
  static ReachLanes EndReach(const ReachConstants& c, const ReachLanes x[3]) {
    using Bits2 = long long __attribute__((vector_size(16)));
    const auto magnitude = [](ReachLanes v) {
      return std::bit_cast<ReachLanes>(std::bit_cast<Bits2>(v) &
                                       Bits2{0x7fffffffffffffffLL, 0x7fffffffffffffffLL});
    };
    return magnitude(c.nx * x[0] + c.ny * x[1]) + c.r * magnitude(x[2]);
  }

  /// The four corners' travels f_k (m) and rates df_k/dt (m/s) at one state of a deck.
  struct CornerState {
    std::array<double, 4> f{};
    std::array<double, 4> rate{};
  };

  /// Scan's work on deck d at a step's end, for a caller that steps the deck itself, whose reach
  /// test (MayReach) passed and that defers the corners' root searches: s0 and s1 the deck's (x,
  /// y, theta, u_x, u_y, u_theta) at the ends of a step of h_s (s). Raises `best` (m) to the
  /// corners' travels at the step's end and keeps that end as Scan does (the same evaluations,
  /// the same bits). Returns the corners (bit k: corner k) whose rate changes sign inside the
  /// step with Scan's cheap peak bound, written to bound[k] (m), above the raised maximum: every
  /// corner Scan could search from a maximum at least that large [docs/theory.md §3.20].
  int ScanEnd(int d, const std::array<double, 6>& s0, const std::array<double, 6>& s1, double h_s,
              double& best, double bound[4]) {
    const auto di = static_cast<std::size_t>(d);
    const Deck& deck = decks_[di];
    DeckEnd& end = end_[di];
    CornerState start;
    const CornerState* c0 = &end.corners;
    if (s0 != end.state) {
      Evaluate(deck, s0[0], s0[1], s0[2], s0[3], s0[4], s0[5], start);
      c0 = &start;
    }
    CornerState c1;
    Evaluate(deck, s1[0], s1[1], s1[2], s1[3], s1[4], s1[5], c1);
    double raised = best;
    for (int k = 0; k < 4; ++k) {
      raised = std::max(raised, std::abs(c1.f[static_cast<std::size_t>(k)]));
    }
    int deferred = 0;
    for (int k = 0; k < 4; ++k) {
      const auto ki = static_cast<std::size_t>(k);
      const double r0 = c0->rate[ki], r1 = c1.rate[ki];
      if (!(r0 * r1 < 0.0)) continue;
      const double b = std::max(std::abs(c0->f[ki]), std::abs(c1.f[ki])) +
                       0.5 * h_s * std::min(std::abs(r0), std::abs(r1));
      if (b > raised) {
        bound[k] = b;
        deferred |= 1 << k;
      }
    }
    best = raised;
    end.corners = c1;
    end.state = s1;
    return deferred;
  }

  /// Deck d's corners at the state s (x, y, theta, u_x, u_y, u_theta): Scan's evaluation.
  CornerState Corners(int d, const std::array<double, 6>& s) const {
    CornerState c;
    Evaluate(decks_[static_cast<std::size_t>(d)], s[0], s[1], s[2], s[3], s[4], s[5], c);
    return c;
  }
  /// Whether Scan's travel bound spares corner k of deck d over a step of h_s (s) whose ends
  /// have the corners c0 and c1: travel_bound (Scan's) below `best` (m).
  template <class TravelBound>
  bool TravelBelow(int d, int k, const CornerState& c0, const CornerState& c1, double h_s,
                   double best, TravelBound& travel_bound) const {
    const Deck& deck = decks_[static_cast<std::size_t>(d)];
    const auto ki = static_cast<std::size_t>(k);
    return travel_bound(3 * d, deck.nx, deck.ny, deck.radius, c0.f[ki], c0.rate[ki], c1.f[ki],
                        c1.rate[ki], h_s) < best;
  }
  /// The travel (m) of corner k of deck d at the root of its rate in [t0, t1] (Scan's search on
  /// component_at, Scan's arguments), the corners at the ends c0 and c1.
  template <class ComponentAt>
  double RootTravel(int d, int k, double t0, double t1, const CornerState& c0,
                    const CornerState& c1, double time_tolerance_s,
                    ComponentAt& component_at) const {
    const auto ki = static_cast<std::size_t>(k);
    bool turned = false;
    return PeakTravel(decks_[static_cast<std::size_t>(d)], 3 * d, k, t0, t1, c0.rate[ki],
                      c1.rate[ki], time_tolerance_s, component_at, turned);
  }

  /// MayReach from its ends' terms in lanes (EndReach's (reach, speed)): the larger reach and the
  /// smaller speed as std::max and std::min take them, then MayReach's operations, the same
  /// answer.
  static bool MayReach(ReachLanes end0, ReachLanes end1, double h_s, double best) {
    const ReachLanes larger = end0 < end1 ? end1 : end0, smaller = end1 < end0 ? end1 : end0;
    const double reach = larger[0] + 0.5 * h_s * smaller[1];
    return !(reach * (1.0 + 1e-12) < best);
  }

  /// MayReach from its ends' terms (EndReach): when neither end nor the interior peak that
  /// Scan's root search could find can reach the running maximum `best` (m), the corners are not
  /// evaluated.
  static bool MayReach(double reach0, double speed0, double reach1, double speed1, double h_s,
                       double best) {
    const double reach = std::max(reach0, reach1) + 0.5 * h_s * std::min(speed0, speed1);
    return !(reach * (1.0 + 1e-12) < best);
  }

 private:
  // One deck's constants: the end-line normal and the corner coefficients of corners 1 and 2.
  struct Deck {
    double nx = 0.0, ny = 0.0;  // n_e = (cos a, -sin a)
    double A[2] = {0.0, 0.0};   // n_e . P_k (m), k = 1, 2
    double B[2] = {0.0, 0.0};   // n_e . (-P_k,y, P_k,x) (m), k = 1, 2
    double radius = 0.0;        // max_k |P_k| (m)
  };
  // The travel of corner k of the deck at DOF b at the root of its rate in [t0, t1] (Brent's
  // method on the dense output); out of line, so the step's common path stays small. `turned`
  // is set when some theta or u_theta it read is not zero (+0 or -0).
  template <class ComponentAt>
  [[gnu::noinline]] double PeakTravel(const Deck& deck, int b, int k, double t0, double t1,
                                      double r0, double r1, double time_tolerance_s,
                                      ComponentAt& component_at, bool& turned) const {
    const auto rate = [&](double t) {
      // theta, u_x, u_y, u_theta: in one read where component_at reads four at once.
      const int at[4] = {b + 2, n_ + b, n_ + b + 1, n_ + b + 2};
      double s[4];
      if constexpr (requires { component_at(t, at, s); }) {
        component_at(t, at, s);
      } else {
        for (int j = 0; j < 4; ++j) s[j] = component_at(t, at[j]);
      }
      turned = turned || s[0] != 0.0 || s[3] != 0.0;
      return Rate(deck, k, s[1], s[2], s[0], s[3]);
    };
    const double x = FindRootBrent(rate, t0, t1, r0, r1, time_tolerance_s).x;
    const double th = component_at(x, b + 2);
    turned = turned || th != 0.0;
    return std::abs(Travel(deck, k, component_at(x, b), component_at(x, b + 1), th));
  }
  // Scan's work for deck d past its reach test: the corners at the step's end, their travel
  // into `best` (the deck's running maximum), and the roots of their rates; out of line.
  template <class ComponentAt, class TravelBound>
  [[gnu::noinline]] void ScanDeck(int d, double t0, const Eigen::Map<const Eigen::VectorXd>& q0,
                                  const Eigen::Map<const Eigen::VectorXd>& u0, double t1,
                                  const Eigen::Map<const Eigen::VectorXd>& q1,
                                  const Eigen::Map<const Eigen::VectorXd>& u1,
                                  double time_tolerance_s, ComponentAt& component_at, double& best,
                                  TravelBound& travel_bound);
  // sin theta and cos theta - 1, by their Taylor series to rounding for |theta| <= 0.01 rad (the
  // rotations of decks; no library call in the time loop), else by std::sin, std::cos.
  static void SinCosMinusOne(double th, double& s, double& c_minus_1) {
    if (std::abs(th) <= 0.01) {
      const double t2 = th * th;
      s = th * (1.0 + t2 * (-1.0 / 6 + t2 * (1.0 / 120 + t2 * (-1.0 / 5040 + t2 / 362880))));
      c_minus_1 = t2 * (-0.5 + t2 * (1.0 / 24 + t2 * (-1.0 / 720 + t2 / 40320)));
      return;
    }
    s = std::sin(th);
    c_minus_1 = std::cos(th) - 1.0;
  }
  // f_k and df_k/dt of deck d at (x, y, theta, u_x, u_y, u_theta). Inline: every scanned
  // step's end.
  static void Evaluate(const Deck& d, double x, double y, double th, double ux, double uy,
                       double uth, CornerState& out) {
    double s = 0.0, c = 0.0;
    SinCosMinusOne(th, s, c);
    const double cos_th = 1.0 + c;
    const double T = d.nx * x + d.ny * y;
    const double T_rate = d.nx * ux + d.ny * uy;
    for (int k = 0; k < 2; ++k) {
      const double g = c * d.A[k] + s * d.B[k];
      const double g_rate = uth * (-s * d.A[k] + cos_th * d.B[k]);
      // Corners k and k + 2 are opposite: P_{k+2} = -P_k.
      out.f[static_cast<std::size_t>(k)] = T + g;
      out.f[static_cast<std::size_t>(k + 2)] = T - g;
      out.rate[static_cast<std::size_t>(k)] = T_rate + g_rate;
      out.rate[static_cast<std::size_t>(k + 2)] = T_rate - g_rate;
    }
  }
  // The rate of corner k alone. Inline: every iteration of a rate's root search.
  static double Rate(const Deck& d, int k, double ux, double uy, double th, double uth) {
    const int j = k % 2;
    const double sign = k < 2 ? 1.0 : -1.0;
    double s = 0.0, c = 0.0;
    SinCosMinusOne(th, s, c);
    return d.nx * ux + d.ny * uy + sign * uth * (-s * d.A[j] + (1.0 + c) * d.B[j]);
  }
  // The travel of corner k alone.
  static double Travel(const Deck& d, int k, double x, double y, double th);

  std::vector<Deck> decks_;
  int n_ = 0;  // n_dof
  // A deck's corner states at the last step's end and its state there (x, y, theta, u_x, u_y,
  // u_theta), reused as the next step's start when that state is the same bits (no impact or
  // projection in between).
  struct DeckEnd {
    CornerState corners;
    std::array<double, 6> state{};
  };
  std::vector<DeckEnd> end_;  // per deck, in one block
};

template <class ComponentAt, class TravelBound>
void CornerTravelTracker::ScanDeck(int d, double t0, const Eigen::Map<const Eigen::VectorXd>& q0,
                                   const Eigen::Map<const Eigen::VectorXd>& u0, double t1,
                                   const Eigen::Map<const Eigen::VectorXd>& q1,
                                   const Eigen::Map<const Eigen::VectorXd>& u1,
                                   double time_tolerance_s, ComponentAt& component_at, double& best,
                                   TravelBound& travel_bound) {
  const auto di = static_cast<std::size_t>(d);
  const Deck& deck = decks_[di];
  const int b = 3 * d;
  const double r = deck.radius;
  // The step's start: the last step's end unless an impact or a projection moved the state.
  const std::array<double, 6> s0{q0[b], q0[b + 1], q0[b + 2], u0[b], u0[b + 1], u0[b + 2]};
  DeckEnd& end = end_[di];
  if (s0 != end.state) {
    Evaluate(deck, s0[0], s0[1], s0[2], s0[3], s0[4], s0[5], end.corners);
  }
  const CornerState& c0 = end.corners;
  const std::array<double, 6> s1{q1[b], q1[b + 1], q1[b + 2], u1[b], u1[b + 1], u1[b + 2]};
  CornerState c1;
  Evaluate(deck, s1[0], s1[1], s1[2], s1[3], s1[4], s1[5], c1);
  for (int k = 0; k < 4; ++k) {
    best = std::max(best, std::abs(c1.f[static_cast<std::size_t>(k)]));
  }
  // A corner searched over a deck that did not turn at any instant its search read: `still`.
  // Another corner with the same end rates (bit for bit, or both zero) would search the same
  // instants and find the same travel [docs/theory.md §3.20], which `best` already holds.
  int still = -1;
  for (int k = 0; k < 4; ++k) {
    const auto ki = static_cast<std::size_t>(k);
    const double r0 = c0.rate[ki], r1 = c1.rate[ki];
    if (!(r0 * r1 < 0.0)) continue;
    if (still >= 0 && r0 == c0.rate[static_cast<std::size_t>(still)] &&
        r1 == c1.rate[static_cast<std::size_t>(still)]) {
      continue;
    }
    // Were the rate linear in t, the peak would exceed the larger end value by
    // min(r0^2, r1^2) (t1 - t0) / (2 (|r0| + |r1|)) <= (t1 - t0) min(|r0|, |r1|) / 4; twice
    // that leaves room for the rate's curvature over a step.
    const double bound = std::max(std::abs(c0.f[ki]), std::abs(c1.f[ki])) +
                         0.5 * (t1 - t0) * std::min(std::abs(r0), std::abs(r1));
    if (!(bound > best)) continue;
    if (travel_bound(b, deck.nx, deck.ny, r, c0.f[ki], r0, c1.f[ki], r1, t1 - t0) < best) {
      continue;
    }
    bool turned = false;
    best = std::max(best,
                    PeakTravel(deck, b, k, t0, t1, r0, r1, time_tolerance_s, component_at, turned));
    if (!turned && still < 0) still = k;
  }
  end.corners = c1;
  end.state = s1;
}

}  // namespace skewbridge::dynamics
