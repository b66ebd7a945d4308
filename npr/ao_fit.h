// Fitting alpha * rho of Hegeman et al. Eq. 6 to a reference ambient visibility (the paper
// chooses it by hand, §4, and suggests a preprocessing step to compute it): least squares
// of V = exp(-k x) over samples (x = the model's f * V_cap at a point, v = the reference
// visibility there, e.g. from npr/ao_reference.h).
#pragma once

#include <vector>

namespace sylva {

struct AlphaRhoSample {
  double weighted_volume = 0;  // x = f * V_cap (CapGeometry::weighted_volume), finite, >= 0
  double visibility = 1;       // v, the reference visibility, [0, 1] (0 = every ray blocked)
  double weight = 1;           // w, the sample's share of the sum of squares, finite, >= 0
};

struct AlphaRhoFit {
  double alpha_rho = 0;            // k >= 0 minimising sum w_i (exp(-k x_i) - v_i)^2
  double rmse = 0;                 // sqrt(sum w_i (exp(-k x_i) - v_i)^2 / sum w_i) at that k
  double log_linear_estimate = 0;  // the starting point: k of -ln v = k x through the origin
  int evaluations = 0;             // of the sum of squares (for tests and benchmarks)
};

// Minimises S(k) = sum_i w_i (exp(-k x_i) - v_i)^2 over k >= 0 (least squares in V, not in log V,
// which would overweight the darkest samples). S is a sum of unimodal terms but need not be
// unimodal itself, so: x is scaled by its maximum; the log-linear estimate k0 (v floored at
// 1e-6 for the logarithm; weighted by w) centres a scan of S over k0 * 2^(j/4), j in [-80, 80],
// plus k = 0; Brent's minimisation (golden section with parabolic steps, relative tolerance 1e-8)
// refines the best scanned k between its neighbours, and Newton steps on S'(k) = 0 (analytic S',
// S'', kept only while they stay in that bracket and do not raise S) polish it to machine
// precision. k = 0 exactly when no sample with x > 0 has v < 1 (S is then non-decreasing).
// The result is capped at k0 * 2^20 when S still falls there (samples saying "opaque" at
// every x > 0). Throws InputError("alpha-rho samples", ...) for no samples, a non-finite or
// negative x or w, v outside [0, 1], or weights summing to 0.
AlphaRhoFit fit_alpha_rho(const std::vector<AlphaRhoSample>& samples);

}  // namespace sylva
