#include "npr/ao_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace sylva {
namespace {

constexpr double kVisibilityFloor = 1e-6;  // for the logarithm of the starting estimate
constexpr int kScanSteps = 80;             // scan k0 * 2^(j/4) for |j| <= kScanSteps
constexpr double kBrentTolerance = 1e-8;   // function values locate k to ~sqrt(eps)
constexpr int kMaxBrentIterations = 200;
constexpr int kMaxNewtonIterations = 20;

struct Objective {
  const std::vector<AlphaRhoSample>* samples;
  double x_scale;  // x_i / x_scale is in [0, 1]
  int* evaluations;

  double operator()(double k) const {
    ++*evaluations;
    double s = 0.0;
    for (const AlphaRhoSample& p : *samples) {
      const double r = std::exp(-k * (p.weighted_volume / x_scale)) - p.visibility;
      s += p.weight * r * r;
    }
    return s;
  }
  // S'(k) and S''(k).
  void derivatives(double k, double& d1, double& d2) const {
    d1 = d2 = 0.0;
    for (const AlphaRhoSample& p : *samples) {
      const double x = p.weighted_volume / x_scale;
      const double e = std::exp(-k * x);
      d1 += -2.0 * p.weight * x * e * (e - p.visibility);
      d2 += 2.0 * p.weight * x * x * e * (2.0 * e - p.visibility);
    }
  }
};

// Brent's minimisation on [lo, hi] starting from x0 (Numerical Recipes, 3rd ed., §10.3).
double brent(const Objective& f, double lo, double hi, double x0) {
  constexpr double kGold = 0.3819660112501051;
  constexpr double kTiny = 1e-300;
  double a = lo, b = hi;
  double x = x0, w = x0, v = x0;
  double fx = f(x), fw = fx, fv = fx;
  double d = 0.0, e = 0.0;
  for (int it = 0; it < kMaxBrentIterations; ++it) {
    const double xm = 0.5 * (a + b);
    const double tol1 = kBrentTolerance * std::abs(x) + kTiny, tol2 = 2.0 * tol1;
    if (std::abs(x - xm) <= tol2 - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::abs(e) > tol1) {  // try a parabola through x, w, v
      double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      const double etemp = e;
      e = d;
      if (!(std::abs(p) >= std::abs(0.5 * q * etemp) || p <= q * (a - x) || p >= q * (b - x))) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = std::copysign(tol1, xm - x);
        golden = false;
      }
    }
    if (golden) {
      e = x >= xm ? a - x : b - x;
      d = kGold * e;
    }
    const double u = std::abs(d) >= tol1 ? x + d : x + std::copysign(tol1, d);
    const double fu = f(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w, fv = fw;
      w = x, fw = fx;
      x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw;
        w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return x;
}

}  // namespace

AlphaRhoFit fit_alpha_rho(const std::vector<AlphaRhoSample>& samples) {
  if (samples.empty()) throw InputError("alpha-rho samples", "need at least one sample, got none");
  double x_max = 0.0, total_weight = 0.0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const AlphaRhoSample& s = samples[i];
    if (!(std::isfinite(s.weighted_volume) && s.weighted_volume >= 0.0))
      throw InputError("alpha-rho samples",
                       "sample " + std::to_string(i) + ": f * V_cap must be finite and >= 0");
    if (!(s.visibility >= 0.0 && s.visibility <= 1.0))
      throw InputError("alpha-rho samples",
                       "sample " + std::to_string(i) + ": visibility must be in [0, 1]");
    if (!(std::isfinite(s.weight) && s.weight >= 0.0))
      throw InputError("alpha-rho samples",
                       "sample " + std::to_string(i) + ": weight must be finite and >= 0");
    x_max = std::max(x_max, s.weighted_volume);
    total_weight += s.weight;
  }
  if (!(total_weight > 0.0) || !std::isfinite(total_weight))
    throw InputError("alpha-rho samples", "the weights sum to 0 (or overflow)");

  AlphaRhoFit fit;
  Objective f{&samples, x_max > 0.0 ? x_max : 1.0, &fit.evaluations};
  // Log-linear least squares through the origin on the scaled x.
  double num = 0.0, den = 0.0, pull = 0.0;
  for (const AlphaRhoSample& s : samples) {
    const double x = s.weighted_volume / f.x_scale;
    num += s.weight * x * -std::log(std::max(s.visibility, kVisibilityFloor));
    den += s.weight * x * x;
    pull += s.weight * x * (1.0 - s.visibility);  // -S'(0) / 2
  }
  if (!(pull > 0.0) || !(den > 0.0) || !(num > 0.0)) {  // S is non-decreasing: k = 0
    fit.rmse = std::sqrt(f(0.0) / total_weight);
    return fit;
  }
  const double k0 = num / den;

  // Scan, then refine between the best scanned value's neighbours.
  std::vector<double> ks{0.0};
  for (int j = -kScanSteps; j <= kScanSteps; ++j)
    ks.push_back(k0 * std::exp2(j / 4.0));
  size_t best = 0;
  double best_s = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < ks.size(); ++i) {
    const double s = f(ks[i]);
    if (s < best_s) best_s = s, best = i;
  }
  double k = ks[best];
  if (best + 1 < ks.size()) {
    const double lo = ks[best == 0 ? 0 : best - 1], hi = ks[best + 1];
    k = brent(f, lo, hi, k);
    // Newton on S'(k) = 0 takes k from ~1e-8 to machine precision; a step is kept only when
    // it stays in the bracket and does not raise S.
    double s_k = f(k);
    for (int it = 0; it < kMaxNewtonIterations; ++it) {
      double d1, d2;
      f.derivatives(k, d1, d2);
      if (!(d2 > 0.0)) break;
      const double next = k - d1 / d2;
      if (!(next >= lo && next <= hi)) break;
      const double s_next = f(next);
      if (!(s_next <= s_k)) break;
      const bool done = std::abs(next - k) <= 1e-15 * std::abs(k);
      k = next, s_k = s_next;
      if (done) break;
    }
  }
  fit.alpha_rho = std::max(0.0, k) / f.x_scale;
  fit.log_linear_estimate = k0 / f.x_scale;
  fit.rmse = std::sqrt(f(std::max(0.0, k)) / total_weight);
  return fit;
}

}  // namespace sylva
