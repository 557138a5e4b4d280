#include "energy/window_bound.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "energy/window_terms.hpp"

namespace ecorail::energy {

namespace {

using window_terms::kNone;

// Thrown where WindowBoundOptions::stop ends the work (never inside a parallel region).
struct Stopped {};

// The options' stop, asked from any thread (a parallel loop skips its remaining rows once it
// returned true, then the serial code after the loop throws Stopped).
class StopCheck {
 public:
  explicit StopCheck(const std::function<bool()>& stop) : stop_(stop) {}
  bool operator()() {
    if (hit_.load(std::memory_order_relaxed)) return true;
    if (stop_ && stop_()) hit_.store(true, std::memory_order_relaxed);
    return hit_.load(std::memory_order_relaxed);
  }
  void throw_if_hit() {
    if ((*this)()) throw Stopped{};
  }

 private:
  const std::function<bool()>& stop_;
  std::atomic<bool> hit_{false};
};

using window_terms::active_seconds;
using window_terms::core_min_s;
using window_terms::divisor_at_most;
using window_terms::Grid;
using window_terms::grid_of;

// Pair tables on the 1 s grid: Q(g, s) what a train at offset >= s exchanges with one g seconds
// behind it (both directions), S(s) a train's own bins from s, P(g) = Q(g, g) the whole
// exchange of two trains g apart (min is superadditive, so these bound their fine-grid sums),
// E(s) = sum from s of max(R, T) on the fine grid: the most a train can add to the used energy
// of its bins (min(x + a, y + b) - min(x, y) <= max(a, b)).
struct PairTables {
  int L = 0;              // active seconds: no power at offsets >= L
  std::vector<double> q;  // (L + 1) x (L + 2)
  std::vector<double> self, tail;
  double Q(long g, long s) const {
    if (g < 0 || g > L || s > L) return 0.0;
    if (s < 0) s = 0;
    return q[static_cast<std::size_t>(g) * (L + 2) + s];
  }
  double P(long g) const { return Q(g, g); }
  double S(long s) const { return s > L ? 0.0 : self[std::max(0L, s)]; }
  double E(long s) const { return s > L ? 0.0 : tail[std::max(0L, s)]; }
};

PairTables pair_tables(const Grid& g1, const Grid& gf, int active_s) {
  PairTables pt;
  pt.L = active_s;
  const int L = active_s;
  pt.q.assign(static_cast<std::size_t>(L + 1) * (L + 2), 0.0);
  for (int gap = 1; gap <= L; ++gap) {
    double* row = &pt.q[static_cast<std::size_t>(gap) * (L + 2)];
    for (int tau = L; tau >= 0; --tau) {
      const double x =
          tau >= gap ? std::min(g1.r(tau), g1.t(tau - gap)) + std::min(g1.t(tau), g1.r(tau - gap))
                     : 0.0;
      row[tau] = row[tau + 1] + x;
    }
  }
  pt.self.assign(L + 2, 0.0);
  for (int tau = L; tau >= 0; --tau)
    pt.self[tau] = pt.self[tau + 1] + std::min(g1.r(tau), g1.t(tau));
  // max is subadditive, so E is summed on the fine grid (a coarse bin's max could be smaller).
  pt.tail.assign(L + 2, 0.0);
  for (long tau = static_cast<long>(L) * gf.q - 1; tau >= 0; --tau)
    pt.tail[tau / gf.q] += std::max(gf.r(tau), gf.t(tau));
  for (int sec = L - 1; sec >= 0; --sec) pt.tail[sec] += pt.tail[sec + 1];
  return pt;
}

struct Cells {
  int hmin = 0, hmax = 0, hc = 0;
  int D = 0;
  int short_cells = 0;  // cells below the core: the first ones (cells ascend with h)
  std::vector<int> of;  // cell of h - hmin
  std::vector<int> lo, hi;
  int cell(int h) const { return of[h - hmin]; }
};

Cells make_cells(int hmin, int hmax, int hc, int width) {
  Cells c;
  c.hmin = hmin, c.hmax = hmax, c.hc = hc;
  c.of.assign(hmax - hmin + 1, 0);
  for (int h = hmin; h <= hmax;) {
    const int end = h < hc ? std::min(hc - 1, h + width - 1) : h;
    for (int x = h; x <= end; ++x) c.of[x - hmin] = c.D;
    c.lo.push_back(h);
    c.hi.push_back(end);
    if (h < hc) ++c.short_cells;
    ++c.D;
    h = end + 1;
  }
  return c;
}

// Everything the DP needs: the triple values W[B][C][A] (A the oldest headway's cell), the
// first two windows' values S[A][B] and the last window's E[A][B], each the largest over the
// cells' members.
struct Tables {
  Cells cells;
  std::vector<double> W, S, E;
  // charge[x][B][C][A]: the most train k can add from t_{k+4} on (it is then fifth newest or
  // older), at the step that adds h_{k+3} (cell C) after h_{k+1}, h_{k+2} (cells A, B), when
  // h_k lies in class x (0 the core, then bands below it): zero unless the four can sum below L.
  std::vector<std::vector<double>> charge;
  // What the DP reads, as floats rounded up (a bound stays a bound; half the memory traffic of
  // doubles): Wf = W (no older train yet), Wc[x] = W + charge[x].
  std::vector<float> Wf;
  std::vector<std::vector<float>> Wc;
  // Classes of h_k (the headway before the state's two): 0 the core, then bands of short cells
  // ever further below it; each a contiguous run of cells [first, end).
  std::vector<int> class_of_cell, class_first, class_end;
  int classes() const { return static_cast<int>(class_first.size()); }
  double active_s = 0.0;
};

// The least float not below v (-inf stays -inf).
float float_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

void max_into(double& slot, double v) {
  if (v > slot) slot = v;
}

// Classes of the headway before the DP state's two: 0 the core, then the short cells in bands
// by their distance below it (WindowBoundOptions::short_band_ends_s, one more band for the rest),
// each a contiguous run of cells, the nearest band first.
void assign_classes(Tables& tb, int hc, const std::vector<int>& band_end_s) {
  const Cells& cl = tb.cells;
  tb.class_of_cell.assign(cl.D, 0);
  tb.class_first = {cl.short_cells};
  tb.class_end = {cl.D};
  const int nb = static_cast<int>(band_end_s.size());
  int prev = 0;
  for (int c = cl.short_cells - 1; c >= 0; --c) {
    int band = 1;
    while (band <= nb && hc - cl.lo[c] > band_end_s[band - 1]) ++band;
    if (band != prev) {
      tb.class_first.push_back(c);
      tb.class_end.push_back(c + 1);
      prev = band;
    }
    tb.class_first.back() = c;
    tb.class_of_cell[c] = tb.classes() - 1;
  }
}

// Charges for a fifth train (train k from t_{k+4} on, when it is fifth newest or older): the
// tighter of two bounds on what it adds, each taken at the least s4 = h_k + .. + h_{k+3} the
// cells and h_k's class allow (both only shrink as s4 grows).
//  - E(s4): at most max(R, T) of train k in every bin.
//  - By pairs: adding train k to the newer trains N of a bin adds at most
//    min(R_k, T_N) + min(T_k, R_N) + min(R_k, T_k) <= self + sum_i (min(R_k, T_i) + min(T_k,
//    R_i)), so train k adds at most S(s4) plus, for each newer train i, Q(g_i, s4) at its gap g_i
//    from train k: k+1..k+4 at h_k, h_k + a, h_k + a + b and s4 (each the largest over the range
//    the cells and the class allow), k+5 and later at the largest P beyond their least gap.
// The charge is zero where the four cannot sum below L (train k is then done by t_{k+4}). h_k
// also keeps the deficit: the four miss 4 hmax by at most the span's deficit.
void fifth_train_charges(Tables& tb, const PairTables& pt, const FleetLimits& p, int threads) {
  const Cells& cl = tb.cells;
  const int D = cl.D, L = pt.L;
  const long hmin = p.headway_min_s, hmax = p.headway_max_s;
  const long deficit = static_cast<long>(p.trains - 1) * hmax - p.span_s;
  const int K = 16;  // block of gaps for the range maxima (a block's max bounds its members)
  const int nblk = L / K + 1;
  std::vector<double> qblock(static_cast<std::size_t>(L + 1) * nblk, 0.0);
  for (int gap = 0; gap <= L; ++gap)
    for (int s = 0; s <= L; ++s) {
      double& m = qblock[static_cast<std::size_t>(s) * nblk + gap / K];
      m = std::max(m, pt.Q(gap, s));
    }
  // The most Q(g, s) over g in [g_lo, g_hi] (whole blocks: a superset of the range).
  auto range_max = [&](long g_lo, long g_hi, long s) {
    g_lo = std::max(0L, g_lo), g_hi = std::min<long>(L, g_hi);
    if (g_lo > g_hi || s > L) return 0.0;
    s = std::max(0L, s);
    const double* row = &qblock[static_cast<std::size_t>(s) * nblk];
    double m = 0.0;
    for (long blk = g_lo / K; blk <= g_hi / K; ++blk) m = std::max(m, row[blk]);
    return m;
  };
  // The largest P(g) over g >= gap (P is zero from L on).
  std::vector<double> p_beyond(L + 2, 0.0);
  for (int g = L; g >= 0; --g) p_beyond[g] = std::max(p_beyond[g + 1], pt.P(g));
  const int nx = tb.classes();
  tb.charge.assign(nx, {});
  for (int x = 0; x < nx; ++x) {
    const long class_lo = cl.lo[tb.class_first[x]], class_hi = cl.hi[tb.class_end[x] - 1];
    tb.charge[x].assign(static_cast<std::size_t>(D) * D * D, 0.0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (int A = 0; A < D; ++A)
      for (int B = 0; B < D; ++B)
        for (int C = 0; C < D; ++C) {
          const long lo3 = static_cast<long>(cl.lo[A]) + cl.lo[B] + cl.lo[C];
          const long hi3 = static_cast<long>(cl.hi[A]) + cl.hi[B] + cl.hi[C];
          const long hk_lo = std::max(class_lo, 4L * hmax - deficit - hi3);
          const long hk_hi = std::min(class_hi, static_cast<long>(L) - 1 - lo3);
          if (hk_lo > hk_hi) continue;
          const long s4 = std::max(hk_lo + lo3, 4L * hmax - deficit);
          const long loA = cl.lo[A], loAB = loA + cl.lo[B];
          const long hiA = cl.hi[A], hiAB = hiA + cl.hi[B];
          double pairs = pt.S(s4) + range_max(hk_lo, hk_hi, s4) +
                         range_max(hk_lo + loA, hk_hi + hiA, s4) +
                         range_max(hk_lo + loAB, hk_hi + hiAB, s4) + range_max(s4, hk_hi + hi3, s4);
          for (long m = 5;; ++m) {  // trains k+5, k+6, ... while one can still meet train k
            const long g = std::max(s4 + (m - 4) * hmin, m * hmax - deficit);
            if (g >= L) break;
            pairs += p_beyond[g];
          }
          tb.charge[x][(static_cast<std::size_t>(B) * D + C) * D + A] = std::min(pt.E(s4), pairs);
        }
  }
}

Tables build_tables(const PowerProfile& profile, const FleetLimits& p, const WindowBoundOptions& o,
                    int threads, StopCheck& stop) {
  Tables tb;
  const int tps = profile.ticks_per_second();
  const int L = active_seconds(profile);
  tb.active_s = L;
  const int hmin = p.headway_min_s, hmax = p.headway_max_s;
  const int hc = core_min_s(L, p);
  tb.cells = make_cells(hmin, hmax, hc, std::max(1, o.short_cell_s));
  const Cells& cl = tb.cells;
  const int D = cl.D;
  const Grid g1 = grid_of(profile, 1);
  const int qf = divisor_at_most(tps, o.bound_ticks_per_second);
  const Grid gf = grid_of(profile, qf);
  // Every feasible timetable's headways miss n hmax by exactly this many seconds, so no run of
  // consecutive headways misses its maximum by more.
  const long deficit = static_cast<long>(p.trains - 1) * hmax - p.span_s;
  const PairTables pt = pair_tables(g1, gf, L);
  tb.W.assign(static_cast<std::size_t>(D) * D * D, kNone);
  tb.S.assign(static_cast<std::size_t>(D) * D, kNone);
  tb.E.assign(static_cast<std::size_t>(D) * D, kNone);
  auto Wat = [&](int A, int B, int C) -> double& {
    return tb.W[(static_cast<std::size_t>(B) * D + C) * D + A];
  };
  // Windows of three trains (oldest at offset a + b, then b, the newest at 0) on grid g: the
  // used energy over the first u bins for u = 0..upto.
  auto three = [](const Grid& g, long off_mid, long off_old, long upto, std::vector<double>& cum) {
    cum.assign(upto + 1, 0.0);
    double s = 0.0;
    for (long u = 0; u < upto; ++u) {
      const double r = g.r(u) + g.r(u + off_mid) + g.r(u + off_old);
      const double t = g.t(u) + g.t(u + off_mid) + g.t(u + off_old);
      s += std::min(r, t);
      cum[u + 1] = s;
    }
  };

  // 1. Triples with a headway below the core, on the 1 s grid, the fourth train by pairs.
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int A = 0; A < D; ++A) {
    if (stop()) continue;
    std::vector<double> cum;
    for (int a = cl.lo[A]; a <= cl.hi[A]; ++a)
      for (int b = hmin; b <= hmax; ++b) {
        const int B = cl.cell(b);
        three(g1, b, a + b, hmax, cum);
        for (int c = hmin; c <= hmax; ++c) {
          if (a >= hc && b >= hc && c >= hc) continue;
          const long s3 = static_cast<long>(a) + b + c;
          if (3L * hmax - s3 > deficit) continue;  // no feasible timetable holds this triple
          // The fourth train by pairs (its older roles are charged by the DP, below).
          const double v = cum[c] + pt.Q(a, s3) + pt.Q(a + b, s3) + pt.P(s3) + pt.S(s3);
          max_into(Wat(A, B, cl.cell(c)), v);
        }
      }
  }
  stop.throw_if_hit();
  // 2. Core triples, exactly on the fine grid: G3 of the window plus the fourth train's
  // increment from t_{k+3} on.
  const window_terms::ExactTerms exact(profile, qf);
  const long q = qf;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int a = hc; a <= hmax; ++a) {
    if (stop()) continue;
    std::vector<double> cum;
    for (int b = hc; b <= hmax; ++b) {
      three(gf, b * q, (a + b) * q, hmax * q, cum);
      for (int c = hc; c <= hmax; ++c) {
        const double x4 = exact.fourth(a, b, c);
        Wat(cl.cell(a), cl.cell(b), cl.cell(c)) = cum[c * q] + x4;
      }
    }
  }
  stop.throw_if_hit();
  assign_classes(tb, hc, o.short_band_ends_s);
  fifth_train_charges(tb, pt, p, threads);
  stop.throw_if_hit();
  // 3. First two windows (train 1 alone over h1, trains 1 and 2 over h2) and the last window
  // (the newest three from t_N on; core pairs on the fine grid, the others on 1 s).
  {
    std::vector<double> self_cum(hmax * q + 1, 0.0);
    for (long u = 0; u < hmax * q; ++u) self_cum[u + 1] = self_cum[u] + std::min(gf.r(u), gf.t(u));
    std::vector<double> cum;
    for (int h1 = hmin; h1 <= hmax; ++h1) {
      cum.assign(hmax * q + 1, 0.0);
      double s = 0.0;
      for (long u = 0; u < hmax * q; ++u) {
        s += std::min(gf.r(u) + gf.r(u + h1 * q), gf.t(u) + gf.t(u + h1 * q));
        cum[u + 1] = s;
      }
      for (int h2 = hmin; h2 <= hmax; ++h2)
        max_into(tb.S[static_cast<std::size_t>(cl.cell(h1)) * D + cl.cell(h2)],
                 self_cum[h1 * q] + cum[h2 * q]);
    }
  }
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int A = 0; A < D; ++A) {
    std::vector<double> cum;
    for (int a = cl.lo[A]; a <= cl.hi[A]; ++a)
      for (int b = hmin; b <= hmax; ++b) {
        const bool core = a >= hc && b >= hc;
        const Grid& g = core ? gf : g1;
        three(g, b * static_cast<long>(g.q), (a + b) * static_cast<long>(g.q), g.bins, cum);
        max_into(tb.E[static_cast<std::size_t>(A) * D + cl.cell(b)], cum.back());
      }
  }
  const int nx = tb.classes();
  tb.Wf.resize(tb.W.size());
  tb.Wc.assign(nx, std::vector<float>(tb.W.size()));
  for (std::size_t i = 0; i < tb.W.size(); ++i) {
    tb.Wf[i] = float_up(tb.W[i]);
    for (int x = 0; x < nx; ++x) tb.Wc[x][i] = float_up(tb.W[i] + tb.charge[x][i]);
  }
  std::vector<double>().swap(tb.W);
  for (int x = 0; x < nx; ++x) std::vector<double>().swap(tb.charge[x]);
  return tb;
}

struct DualRun {
  double value = kNone;  // the bound for this multiplier
  long excess_s = 0;     // sum of the maximiser's headways less the span
  std::vector<int> headways;
};

// max over sequences of the window terms + mu (sum h - span); short cells count at the end
// that mu favours.
DualRun run_dual(const Tables& tb, const FleetLimits& p, double mu, int threads, long& work,
                 StopCheck& stop) {
  const Cells& cl = tb.cells;
  const int D = cl.D, n = p.trains - 1;
  auto hx = [&](int C) { return mu >= 0.0 ? cl.hi[C] : cl.lo[C]; };
  // V[x][B][A]: best value with last headways in cells A, B, the one before A of class x.
  const std::size_t DD = static_cast<std::size_t>(D) * D;
  const int nx = tb.classes();
  std::vector<double> V(nx * DD, kNone), next(nx * DD);
  for (int A = 0; A < D; ++A)
    for (int B = 0; B < D; ++B)
      V[static_cast<std::size_t>(B) * D + A] =
          tb.S[static_cast<std::size_t>(A) * D + B] + mu * (hx(A) + hx(B));
  std::vector<std::vector<std::uint16_t>> back(n + 1);
  for (int j = 3; j <= n; ++j) {
    stop.throw_if_hit();
    back[j].assign(nx * DD, 0);
    std::vector<std::uint16_t>& bp = back[j];
    const bool charged = j >= 4;  // train j-3 exists
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int B = 0; B < D; ++B) {
      for (int C = 0; C < D; ++C) {
        const std::size_t row = (static_cast<std::size_t>(B) * D + C) * D;
        // y: the class of the oldest headway A (its cells are contiguous). The max first (a
        // plain reduction the compiler vectorises), then the first A that reaches it.
        for (int y = 0; y < nx; ++y) {
          const int a0 = tb.class_first[y], a1 = tb.class_end[y];
          double best = kNone;
          int arg = 0;
          for (int x = 0; x < nx; ++x) {
            const double* v = &V[x * DD + static_cast<std::size_t>(B) * D];
            const float* w = charged ? &tb.Wc[x][row] : &tb.Wf[row];
            double m = kNone;
            for (int A = a0; A < a1; ++A) {
              const double val = v[A] + static_cast<double>(w[A]);
              m = val > m ? val : m;
            }
            if (m > best) {
              int A = a0;
              while (v[A] + static_cast<double>(w[A]) != m) ++A;
              best = m;
              arg = A | (x << 12);
            }
          }
          const std::size_t at = y * DD + static_cast<std::size_t>(C) * D + B;
          next[at] = best + mu * hx(C);
          bp[at] = static_cast<std::uint16_t>(arg);
        }
      }
    }
    V.swap(next);
    work += static_cast<long>(nx) * D * D * D;
  }
  DualRun out;
  int bestA = 0, bestB = 0, bestX = 0;
  for (int x = 0; x < nx; ++x)
    for (int A = 0; A < D; ++A)
      for (int B = 0; B < D; ++B) {
        const double v = V[x * DD + static_cast<std::size_t>(B) * D + A] +
                         tb.E[static_cast<std::size_t>(A) * D + B];
        if (v > out.value) out.value = v, bestA = A, bestB = B, bestX = x;
      }
  out.value -= mu * p.span_s;
  std::vector<int> cells(n);
  cells[n - 1] = bestB;
  if (n >= 2) cells[n - 2] = bestA;
  int x = bestX;
  for (int j = n; j >= 3; --j) {
    const std::uint16_t b =
        back[j][x * DD + static_cast<std::size_t>(cells[j - 1]) * D + cells[j - 2]];
    cells[j - 3] = b & 0xfff;
    x = b >> 12;
  }
  long sum = 0;
  for (int C : cells) {
    out.headways.push_back(hx(C));
    sum += hx(C);
  }
  out.excess_s = sum - p.span_s;
  return out;
}

}  // namespace

bool WindowBoundOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (bound_ticks_per_second < 1 || bound_ticks_per_second > 100)
    return fail("bound_ticks_per_second: expected 1 to 100");
  if (short_cell_s < 1 || short_cell_s > 1000) return fail("short_cell_s: expected 1 to 1000 s");
  if (max_dual_evaluations < 1 || max_dual_evaluations > 200)
    return fail("max_dual_evaluations: expected 1 to 200");
  if (!(multiplier_tolerance >= 0.0 && multiplier_tolerance < 1.0))
    return fail("multiplier_tolerance: expected a fraction in [0, 1)");
  if (threads < 0 || threads > 1024) return fail("threads: expected 0 (default) to 1024");
  if (short_band_ends_s.size() > 14) return fail("short_band_ends_s: expected at most 14 bands");
  for (std::size_t i = 0; i < short_band_ends_s.size(); ++i)
    if (short_band_ends_s[i] < 1 || (i > 0 && short_band_ends_s[i] <= short_band_ends_s[i - 1]))
      return fail("short_band_ends_s: expected ascending positive seconds");
  return true;
}

namespace {

std::string not_applicable(const PowerProfile& profile, const FleetLimits& p) {
  if (p.headway_classes > 1) return "peak windows (two headway classes)";
  if (profile.sections() != 1) return "more than one supply section";
  if (p.trains < 3) return "fewer than three trains";
  if (p.headway_max_s - p.headway_min_s > 4000) return "headway range wider than 4000 s";
  return "";
}

}  // namespace

WindowBound window_used_regen_bound(const PowerProfile& profile, const FleetLimits& p,
                                    const WindowBoundOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument(why);
  WindowBound out;
  out.why_not = not_applicable(profile, p);
  if (!out.why_not.empty()) return out;
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  StopCheck stop(o.stop);
  Tables tb;
  try {
    tb = build_tables(profile, p, o, threads, stop);
  } catch (const Stopped&) {
    out.stopped = true;
    out.why_not = "stopped before its tables were built";
    return out;
  }
  out.tables_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.applicable = true;
  out.active_s = tb.active_s;
  out.core_min_s = tb.cells.hc;
  if (tb.cells.D > 4095) throw std::length_error("window bound: too many headway cells");
  // Bisection on the multiplier: the excess of the maximiser's sum is a subgradient of the
  // (convex) dual, non-decreasing in mu.
  long work = 0;
  auto eval = [&](double mu) {
    DualRun r = run_dual(tb, p, mu, threads, work, stop);
    ++out.evaluations;
    if (out.evaluations == 1 || r.value < out.bound_used_J) {
      out.bound_used_J = r.value;
      out.mu_J_per_s = mu;
      out.best_maximiser = r.headways;
    }
    out.maximisers.push_back(r.headways);
    return r;
  };
  // The dual g(mu) is convex with subgradient excess(mu). With ends of opposite excess, its
  // minimum lies between them and is at least where their tangents cross: the search stops
  // once the best bound is within the tolerance of that.
  struct End {
    double mu = 0.0, g = 0.0;
    long e = 0;
  };
  auto tangent_floor = [](const End& a, const End& b) {
    const double mu = (b.g - a.g + a.e * a.mu - b.e * b.mu) / static_cast<double>(a.e - b.e);
    return a.g + a.e * (mu - a.mu);
  };
  // Every multiplier's value is a bound (weak duality): a stop keeps the best one so far.
  try {
    DualRun at0 = eval(0.0);
    out.dual_floor_J = at0.excess_s == 0 ? at0.value : kNone;
    if (at0.excess_s != 0) {
      // Bracket: move away from 0 against the excess, quadrupling, until the excess changes sign;
      // first to where the tangent at 0 reaches zero (g is never negative: every term is).
      const double dir = at0.excess_s > 0 ? -1.0 : 1.0;
      End inner{0.0, at0.value, at0.excess_s};
      End outer{
          dir * std::max(1e3, std::fabs(at0.value) / std::fabs(static_cast<double>(at0.excess_s))),
          0.0, 0};
      DualRun r = eval(outer.mu);
      while ((r.excess_s > 0) == (at0.excess_s > 0) && r.excess_s != 0 &&
             out.evaluations < o.max_dual_evaluations) {
        inner = {outer.mu, r.value, r.excess_s};
        outer.mu *= 4.0;
        r = eval(outer.mu);
      }
      outer.g = r.value, outer.e = r.excess_s;
      if (r.excess_s == 0) out.dual_floor_J = r.value;
      while (r.excess_s != 0 && (outer.e > 0) != (at0.excess_s > 0) &&
             out.evaluations < o.max_dual_evaluations) {
        out.dual_floor_J = tangent_floor(inner, outer);
        if (out.bound_used_J - out.dual_floor_J <= o.multiplier_tolerance * out.bound_used_J) break;
        // Next: where the tangents cross (g is piecewise linear, so this ends), kept off the
        // bracket's ends by a tenth of its width.
        const double width = outer.mu - inner.mu;
        const double cross = (outer.g - inner.g + inner.e * inner.mu - outer.e * outer.mu) /
                             static_cast<double>(inner.e - outer.e);
        const double t = std::clamp((cross - inner.mu) / width, 0.1, 0.9);
        const double mid = inner.mu + t * width;
        const DualRun m = eval(mid);
        if (m.excess_s == 0) {
          out.dual_floor_J = m.value;
          break;
        }
        if ((m.excess_s > 0) == (at0.excess_s > 0))
          inner = {mid, m.value, m.excess_s};
        else
          outer = {mid, m.value, m.excess_s};
      }
    }
  } catch (const Stopped&) {
    out.stopped = true;
    if (out.evaluations == 0) {
      out.applicable = false;
      out.why_not = "stopped before its first multiplier";
      return out;
    }
  }
  // Round-off: every term is a sum of at most a few hundred thousand doubles of at most 1e9 J.
  out.bound_used_J += 1e-9 * std::fabs(out.bound_used_J) + 1e-3;
  out.dp_transitions = work;
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

std::string window_cut_short(const WindowBound& w) {
  const std::string cut = "the window bound cut short by the time limit ";
  if (w.evaluations == 0) return cut + "(" + w.why_not + ")";
  return cut + "after " + std::to_string(w.evaluations) + " DP run" +
         (w.evaluations == 1 ? "" : "s");
}

std::vector<std::vector<int>> window_core_maximisers(const PowerProfile& profile,
                                                     const FleetLimits& p,
                                                     const WindowBoundOptions& o) {
  if (!not_applicable(profile, p).empty()) return {};
  FleetLimits core = p;
  core.headway_min_s = core_min_s(active_seconds(profile), p);
  const long n = core.trains - 1;
  if (core.headway_min_s > core.headway_max_s || n * core.headway_min_s > core.span_s) return {};
  return window_used_regen_bound(profile, core, o).maximisers;
}

std::vector<double> window_relaxed_values_J(const PowerProfile& profile, const FleetLimits& p,
                                            const std::vector<std::vector<int>>& sequences,
                                            const WindowBoundOptions& o) {
  std::string why = not_applicable(profile, p);
  if (!why.empty()) throw std::invalid_argument("window bound: " + why);
  const std::function<bool()> no_stop;
  StopCheck never(no_stop);
  const Tables tb = build_tables(profile, p, o, o.threads > 0 ? o.threads : 1, never);
  const Cells& cl = tb.cells;
  const int D = cl.D, n = p.trains - 1;
  std::vector<double> out;
  for (const std::vector<int>& h : sequences) {
    if (static_cast<int>(h.size()) != n)
      throw std::invalid_argument("window bound: one headway per pair of trains expected");
    double v = tb.S[static_cast<std::size_t>(cl.cell(h[0])) * D + cl.cell(h[1])];
    for (int j = 2; j < n; ++j) {
      const std::size_t at =
          (static_cast<std::size_t>(cl.cell(h[j - 1])) * D + cl.cell(h[j])) * D + cl.cell(h[j - 2]);
      // From the third window on, train j-3 (from 1) may be fifth newest: its charge.
      v += j >= 3 ? tb.Wc[tb.class_of_cell[cl.cell(h[j - 3])]][at] : tb.Wf[at];
    }
    v += tb.E[static_cast<std::size_t>(cl.cell(h[n - 2])) * D + cl.cell(h[n - 1])];
    out.push_back(v);
  }
  return out;
}

}  // namespace ecorail::energy
