#include "codec/common/basis.h"

#include <cmath>

namespace dcurve {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;

// x^j * sum_k sigma^k (p x)^(n k) / (n k + j)!: the fundamental solution F_j of
// y^(n) = sigma p^n y, for |p x| small enough that the series converges in a few terms and
// never cancels badly. Stops once a term no longer changes the sum.
double krylov_series(int n, int j, double sigma, double p, double x) {
  double term = 1.0;
  for (int i = 1; i <= j; ++i) term *= x / i;
  double px = p * x;
  double step = sigma;
  for (int i = 0; i < n; ++i) step *= px;
  double sum = term;
  for (int k = 1; k < 40; ++k) {
    double denom = 1.0;
    for (int i = 1; i <= n; ++i) denom *= double(n * (k - 1) + j + i);
    term *= step / denom;
    double next = sum + term;
    if (next == sum) break;
    sum = next;
  }
  return sum;
}

// Second order, T'' = sigma p^2 T: {cosh, sinh/p} or {cos, sin/p} at x.
void krylov2(double sigma, double p, double x, double* out) {
  if (std::fabs(p * x) <= 2.0) {
    out[0] = krylov_series(2, 0, sigma, p, x);
    out[1] = krylov_series(2, 1, sigma, p, x);
  } else if (sigma > 0) {
    out[0] = std::cosh(p * x);
    out[1] = std::sinh(p * x) / p;
  } else {
    out[0] = std::cos(p * x);
    out[1] = std::sin(p * x) / p;
  }
}

// Fourth order, U'''' = +p^4 U, fundamental solutions at x.
void krylov4_exponential(double p, double x, double* out) {
  double a = p * x;
  if (std::fabs(a) <= 2.0) {
    for (int j = 0; j < 4; ++j) out[j] = krylov_series(4, j, 1.0, p, x);
    return;
  }
  double ch = std::cosh(a), sh = std::sinh(a), c = std::cos(a), s = std::sin(a);
  out[0] = 0.5 * (ch + c);
  out[1] = 0.5 * (sh + s) / p;
  out[2] = 0.5 * (ch - c) / (p * p);
  out[3] = 0.5 * (sh - s) / (p * p * p);
}

// Fourth order, U'''' = -p^4 U, fundamental solutions at x.
void krylov4_damped(double p, double x, double* out) {
  double a = p * x;
  if (std::fabs(a) <= 2.0) {
    for (int j = 0; j < 4; ++j) out[j] = krylov_series(4, j, -1.0, p, x);
    return;
  }
  double y = a / kSqrt2;
  double ch = std::cosh(y), sh = std::sinh(y), c = std::cos(y), s = std::sin(y);
  out[0] = ch * c;
  out[1] = (ch * s + sh * c) / (kSqrt2 * p);
  out[2] = sh * s / (p * p);
  out[3] = (ch * s - sh * c) / (kSqrt2 * p * p * p);
}

// Eighth order, U^(8) = p^8 U, fundamental solutions at x.
void krylov8(double p, double x, double* out) {
  if (std::fabs(p * x) <= 4.0) {
    for (int j = 0; j < 8; ++j) out[j] = krylov_series(8, j, 1.0, p, x);
    return;
  }
  double e[4], d[4];
  krylov4_exponential(p, x, e);
  krylov4_damped(p, x, d);
  double p4 = p * p * p * p;
  for (int j = 0; j < 4; ++j) {
    out[j] = 0.5 * (e[j] + d[j]);
    out[j + 4] = 0.5 * (e[j] - d[j]) / p4;
  }
}

// Raw forms above the switch. w in [0, 1] is tau or u; c = w - 1/2.
void raw_exponential_pair(double p, double w, double* out) {
  out[0] = std::exp(-p * w);
  out[1] = std::exp(-p * (1.0 - w));
}

void raw_trig_pair(double p, double w, double* out) {
  out[0] = std::cos(p * (w - 0.5));
  out[1] = std::sin(p * (w - 0.5));
}

void raw_damped_quad(double p, double w, double* out) {
  double b = p / kSqrt2;
  double near = std::exp(-b * w), far = std::exp(-b * (1.0 - w));
  out[0] = near * std::cos(b * w);
  out[1] = near * std::sin(b * w);
  out[2] = far * std::cos(b * (1.0 - w));
  out[3] = far * std::sin(b * (1.0 - w));
}

// Pde8 space set and the exponential half of Pde32 space.
void space4(bool damped, double p, double u, double* out) {
  if (p <= kBasisSwitch) {
    if (damped)
      krylov4_damped(p, u - 0.5, out);
    else
      krylov4_exponential(p, u - 0.5, out);
  } else if (damped) {
    raw_damped_quad(p, u, out);
  } else {
    raw_exponential_pair(p, u, out);
    raw_trig_pair(p, u, out + 2);
  }
}

}  // namespace

int basis_time_count(Basis b) { return b == Basis::Pde8 ? 2 : b == Basis::Pde32 ? 4 : 0; }

int basis_space_count(Basis b) { return b == Basis::Pde8 ? 4 : b == Basis::Pde32 ? 8 : 0; }

int basis_term_count(Basis b) { return basis_time_count(b) * basis_space_count(b); }

void basis_time(Basis b, int basis_case, double time_param, double tau, double* out) {
  double p = time_param;
  if (b == Basis::Pde8) {
    bool trig = (basis_case & 2) != 0;
    if (!trig && p > kBasisSwitch)
      raw_exponential_pair(p, tau, out);
    else
      krylov2(trig ? -1.0 : 1.0, p, tau - 0.5, out);
  } else if (b == Basis::Pde32) {
    if (p <= kBasisSwitch) {
      krylov4_exponential(p, tau - 0.5, out);
    } else {
      raw_exponential_pair(p, tau, out);
      raw_trig_pair(p, tau, out + 2);
    }
  }
}

void basis_space(Basis b, int basis_case, double space_param, double u, double* out) {
  double p = space_param;
  if (b == Basis::Pde8) {
    space4((basis_case & 1) != 0, p, u, out);
  } else if (b == Basis::Pde32) {
    if (p <= kBasisSwitch) {
      krylov8(p, u - 0.5, out);
    } else {
      space4(false, p, u, out);
      space4(true, p, u, out + 4);
    }
  }
}

double evaluate_motion(const CurveMotion& m, double tau, double u) {
  int nt = basis_time_count(m.basis), ns = basis_space_count(m.basis);
  if (nt == 0 || m.coeffs.size() != size_t(nt * ns)) return 0.0;
  double t[4], s[8];
  basis_time(m.basis, m.basis_case, m.time_param, tau, t);
  basis_space(m.basis, m.basis_case, m.space_param, u, s);
  double w = 0.0;
  for (int i = 0; i < nt; ++i) {
    double row = 0.0;
    for (int j = 0; j < ns; ++j) row += double(m.coeffs[size_t(i * ns + j)]) * s[j];
    w += t[i] * row;
  }
  return w;
}

}  // namespace dcurve
