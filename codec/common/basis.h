// The closed-form motion bases of m w_tt = D w_uuuu, evaluated by the encoder AND the decoder
// from this one piece of code. The format spec names these exact functions; changing any
// formula, threshold or ordering below changes the meaning of every stored coefficient.
//
// Conventions
//   tau in [0, 1]: segment-local time. u in [0, 1]: curve parameter.
//   Internally centred: s = tau - 1/2, v = u - 1/2 (halves the argument range, so the
//   Krylov forms below stay well conditioned for twice the parameter range).
//   p = the parameter (mu or alpha for time, delta or r for space), 0 <= p <= 1000.
//   w(tau, u) = sum_{i,j} coeffs[i * basis_space_count(b) + j] * T_i(tau) * U_j(u).
//
// Every family is the solution space of a linear ODE with constant coefficients. Below a
// switch value (p <= kBasisSwitch = 8) the functions are the ODE's FUNDAMENTAL solutions at
// the centre ("Krylov" forms): the unique solutions F_j with F_j^(k)(0) = [j == k], written
// as  F_j(x) = x^j * sum_{k>=0} sigma^k (p x)^(n k) / (n k + j)!  for an ODE y^(n) = sigma p^n y.
// They tend to the monomials 1, x, x^2/2, ... as p -> 0 (the static beam's cubic), where the
// papers' raw exponentials are near singular. Above the switch, the papers' raw functions are
// used, with every growing exponential replaced by the decaying one anchored at the far end
// (e^{p u} ~ e^{-p (1 - u)}), so nothing exceeds 1 in magnitude and nothing overflows at p = 1000.
// Both forms span exactly the papers' function spaces; only the coordinates differ.
//
// Pde8 (2022 paper, eqs. (5)-(8)): basis_case = 2 * time_trig + space_damped.
//   case 0 = eq. (5): T'' = +mu^2 T,  U'''' = +delta^4 U
//   case 1 = eq. (6): T'' = +mu^2 T,  U'''' = -delta^4 U   (the paper's D_w1 = delta / sqrt 2)
//   case 2 = eq. (7): T'' = -mu^2 T,  U'''' = +delta^4 U
//   case 3 = eq. (8): T'' = -mu^2 T,  U'''' = -delta^4 U
//  Time, 2 functions (x = mu s):
//   hyperbolic, mu <= 8: T0 = cosh x,          T1 = sinh(x) / mu
//   hyperbolic, mu  > 8: T0 = e^{-mu tau},     T1 = e^{-mu (1 - tau)}
//   trigonometric, any mu (mu <= 8 Krylov, the same formulas above 8):
//                        T0 = cos x,           T1 = sin(x) / mu
//  Space, 4 functions (a = delta v, for the damped case y = a / sqrt 2, b = delta / sqrt 2):
//   exponential, delta <= 8:  U0 = (cosh a + cos a) / 2,     U1 = (sinh a + sin a) / (2 delta),
//                             U2 = (cosh a - cos a) / (2 delta^2), U3 = (sinh a - sin a) / (2 delta^3)
//   exponential, delta  > 8:  U0 = e^{-delta u}, U1 = e^{-delta (1 - u)}, U2 = cos a, U3 = sin a
//   damped, delta <= 8:       U0 = cosh y cos y,   U1 = (cosh y sin y + sinh y cos y) / (sqrt2 delta),
//                             U2 = sinh y sin y / delta^2, U3 = (cosh y sin y - sinh y cos y) / (sqrt2 delta^3)
//   damped, delta  > 8:       U0 = e^{-b u} cos(b u),         U1 = e^{-b u} sin(b u),
//                             U2 = e^{-b (1-u)} cos(b (1-u)), U3 = e^{-b (1-u)} sin(b (1-u))
//
// Pde32 (2024 paper, eq. (17)): basis_case = 0; 4 time x 8 space functions.
//  Time: the span of {e^{alpha t}, e^{-alpha t}, sin alpha t, cos alpha t}, i.e. T'''' = alpha^4 T:
//   alpha <= 8: the exponential space formulas above with (delta, v) -> (alpha, s)
//   alpha  > 8: T0 = e^{-alpha tau}, T1 = e^{-alpha (1 - tau)}, T2 = cos(alpha s), T3 = sin(alpha s)
//  Space: the span of {e^{+-r u}, sin r u, cos r u, e^{+-rb u} sin rb u, e^{+-rb u} cos rb u},
//  rb = r / sqrt 2, i.e. the solutions of U^(8) = r^8 U:
//   r <= 8: U_j = (E_j + D_j) / 2, U_{j+4} = (E_j - D_j) / (2 r^4), j = 0..3, with E_j, D_j the
//           exponential and damped Pde8 space functions at delta = r (these are the fundamental
//           solutions of U^(8) = r^8 U and tend to v^j / j!, j = 0..7)
//   r  > 8: U0..U3 = exponential Pde8 space functions (delta > 8 branch) at delta = r,
//           U4..U7 = damped Pde8 space functions (delta > 8 branch) at delta = r
//
// Numerics: below |argument| thresholds the Krylov forms are summed from their power series
// (|p x| <= 2 for second and fourth order, <= 4 for eighth order), otherwise from the closed
// forms above; both agree to rounding. Evaluation is allocation-free and deterministic: the
// same inputs give the same bits on one platform (it calls the C library's exp/sin/cos).
#pragma once
#include "codec/common/model.h"

namespace dcurve {

// Above this parameter value the raw (anchored exponential) forms are used.
constexpr double kBasisSwitch = 8.0;
// Largest time or space parameter a file may store (codec/validate enforces it).
constexpr double kBasisMaxParam = 1000.0;

// Pde8: 2, Pde32: 4, Zero: 0.
int basis_time_count(Basis b);
// Pde8: 4, Pde32: 8, Zero: 0.
int basis_space_count(Basis b);
// basis_time_count * basis_space_count.
int basis_term_count(Basis b);

// Writes the basis_time_count(b) time functions at tau (segment-local, [0, 1]) to out.
// time_param is mu (Pde8) or alpha (Pde32), in [0, 1000]; basis_case as in the header.
// Values outside the ranges are evaluated as given (no clamping), never read out of bounds.
void basis_time(Basis b, int basis_case, double time_param, double tau, double* out);

// Writes the basis_space_count(b) space functions at u ([0, 1]) to out.
void basis_space(Basis b, int basis_case, double space_param, double u, double* out);

// w(tau, u) of one stored motion, model units; 0 for Basis::Zero or a malformed coefficient count.
double evaluate_motion(const CurveMotion& m, double tau, double u);

}  // namespace dcurve
