// Moment-based OIT, pass 2: the fraction of a pixel's total absorbance that
// lies in front of a depth, reconstructed from the pixel's moments.
//
// Given moments normalised by b0 (a probability distribution over depth)
// and a fragment at depth x_f, the moment problem has a unique "canonical
// representation" with an atom at x_f and MOMENT_ORDER further atoms
// (Peters & Klein 2015, moment shadow mapping; the paper's section 3):
//   - the further atoms are the roots of the kernel polynomial
//     K(x) = e(x)^T M^-1 e(x_f), M the Hankel (power) or Toeplitz
//     (trigonometric) matrix of the biased moments, e(x) = (1, x, .., x^m);
//   - each atom x weighs 1 / (e(x)^H M^-1 e(x)) (its Christoffel number).
// The mass strictly in front of x_f in that representation is the sharpest
// lower bound on the absorbance in front of x_f that the moments allow
// (power moments; for trigonometric moments the same sum taken along the
// circle from the wrapping zone, as in the paper); the atom at x_f itself is
// the gap to the upper bound. The paper's overestimation beta interpolates:
// fraction = lower + beta * (weight of the atom at x_f).
// Both matrices are factored by Cholesky; e^H M^-1 e = |L^-1 e|^2.
// The roots are found by the Aberth-Ehrlich iteration (any degree up to 4,
// simultaneous, cubically convergent for simple roots, which the kernel
// polynomial of a positive definite matrix has).
#include "algorithms/moment_oit/moments.glsl"
#include "algorithms/moment_oit/bindings.h"

#define ABERTH_ITERATIONS 12
#define MATRIX_SIZE (MOMENT_ORDER + 1)

vec2 complex_mul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 complex_div(vec2 a, vec2 b) { return complex_mul(a, vec2(b.x, -b.y)) / dot(b, b); }
vec2 complex_conj(vec2 a) { return vec2(a.x, -a.y); }
bool is_finite(vec2 a) { return !any(isnan(a)) && !any(isinf(a)); }

// The MOMENT_ORDER roots of sum c[j] z^j (complex coefficients, c[ORDER] != 0).
void polynomial_roots(vec2 c[MATRIX_SIZE], out vec2 roots[MOMENT_ORDER]) {
  const vec2 lead = c[MOMENT_ORDER];
  for (int j = 0; j <= MOMENT_ORDER; ++j) c[j] = complex_div(c[j], lead);
  // Starting points on the unit circle, off the real axis (real roots of
  // the power case and unit-circle roots of the trigonometric case alike).
  for (int k = 0; k < MOMENT_ORDER; ++k) {
    const float angle = 2.0 * MOMENT_PI * float(k) / float(MOMENT_ORDER) + 0.4;
    roots[k] = vec2(cos(angle), sin(angle));
  }
  for (int iteration = 0; iteration < ABERTH_ITERATIONS; ++iteration) {
    for (int k = 0; k < MOMENT_ORDER; ++k) {
      const vec2 z = roots[k];
      vec2 p = c[MOMENT_ORDER], dp = vec2(0.0);
      for (int j = MOMENT_ORDER - 1; j >= 0; --j) {
        dp = complex_mul(dp, z) + p;
        p = complex_mul(p, z) + c[j];
      }
      const vec2 newton = complex_div(p, dp);
      vec2 repulsion = vec2(0.0);
      for (int j = 0; j < MOMENT_ORDER; ++j)
        if (j != k) repulsion += complex_div(vec2(1.0, 0.0), z - roots[j]);
      const vec2 step = complex_div(newton, vec2(1.0, 0.0) - complex_mul(newton, repulsion));
      if (is_finite(step)) roots[k] = z - step;
    }
  }
}

// 1 / x, and 0 where x is 0 or not finite (an atom that does not count).
float christoffel(float squared_norm) {
  const float w = 1.0 / squared_norm;
  return isnan(w) || isinf(w) ? 0.0 : w;
}

#if TRIGONOMETRIC
// L of the Cholesky factorisation L L^H of the Hermitian Toeplitz matrix
// T[j][k] = c_(j-k) (c_-k = conj c_k), diagonal real.
void factor(const vec2 c[MATRIX_SIZE], out vec2 L[MATRIX_SIZE][MATRIX_SIZE]) {
  for (int i = 0; i < MATRIX_SIZE; ++i) {
    for (int j = 0; j <= i; ++j) {
      vec2 s = c[i - j];
      for (int k = 0; k < j; ++k) s -= complex_mul(L[i][k], complex_conj(L[j][k]));
      L[i][j] = i == j ? vec2(sqrt(max(s.x, 1e-30)), 0.0) : s / L[j][j].x;
    }
    for (int j = i + 1; j < MATRIX_SIZE; ++j) L[i][j] = vec2(0.0);
  }
}

// y = L^-1 e(theta); returns |y|^2 = e^H T^-1 e.
float forward(const vec2 L[MATRIX_SIZE][MATRIX_SIZE], float theta, out vec2 y[MATRIX_SIZE]) {
  float norm = 0.0;
  for (int i = 0; i < MATRIX_SIZE; ++i) {
    vec2 s = vec2(cos(float(i) * theta), sin(float(i) * theta));
    for (int k = 0; k < i; ++k) s -= complex_mul(L[i][k], y[k]);
    y[i] = s / L[i][i].x;
    norm += dot(y[i], y[i]);
  }
  return norm;
}

float front_fraction(const float normalized[MOMENT_COUNT], float warped_depth) {
  // Biased towards the uniform distribution on the circle (all c_k = 0 for
  // k > 0), which keeps T positive definite: T' = (1 - bias) T + bias I.
  vec2 c[MATRIX_SIZE];
  c[0] = vec2(1.0, 0.0);
  for (int k = 1; k <= MOMENT_ORDER; ++k)
    c[k] = (1.0 - moment_params.moment_bias) * vec2(normalized[2 * k - 2], normalized[2 * k - 1]);
  vec2 L[MATRIX_SIZE][MATRIX_SIZE];
  factor(c, L);
  const float theta = moment_angle(warped_depth);
  vec2 y[MATRIX_SIZE];
  const float own_weight = christoffel(forward(L, theta, y));
  // q = L^-H y = T^-1 e(theta); the kernel polynomial's coefficients are conj(q).
  vec2 q[MATRIX_SIZE];
  for (int i = MATRIX_SIZE - 1; i >= 0; --i) {
    vec2 s = y[i];
    for (int k = i + 1; k < MATRIX_SIZE; ++k) s -= complex_mul(complex_conj(L[k][i]), q[k]);
    q[i] = s / L[i][i].x;
  }
  for (int i = 0; i < MATRIX_SIZE; ++i) q[i] = complex_conj(q[i]);
  vec2 roots[MOMENT_ORDER];
  polynomial_roots(q, roots);
  float lower = 0.0;
  for (int k = 0; k < MOMENT_ORDER; ++k) {
    // The roots lie on the unit circle; their angle from the wrapping zone
    // (at -pi = pi) orders them against the fragment's.
    const float angle = atan(roots[k].y, roots[k].x);
    if (angle < theta) lower += christoffel(forward(L, angle, y));
  }
  return clamp(lower + moment_params.overestimation * own_weight, 0.0, 1.0);
}
#else
// Bias targets: moments of a distribution inside the moment space, so that
// (1 - bias) b + bias b* is strictly positive definite; the paper's vectors.
#if MOMENT_COUNT == 4
const float kBiasVector[4] = float[4](0.0, 0.375, 0.0, 0.375);
#elif MOMENT_COUNT == 6
const float kBiasVector[6] = float[6](0.0, 0.48, 0.0, 0.451, 0.0, 0.45);
#else
const float kBiasVector[8] = float[8](0.0, 0.75, 0.0, 0.676666667, 0.0, 0.63, 0.0, 0.600303030);
#endif

// L of the Cholesky factorisation L L^T of the Hankel matrix H[i][j] = h[i + j].
void factor(const float h[2 * MOMENT_ORDER + 1], out float L[MATRIX_SIZE][MATRIX_SIZE]) {
  for (int i = 0; i < MATRIX_SIZE; ++i) {
    for (int j = 0; j <= i; ++j) {
      float s = h[i + j];
      for (int k = 0; k < j; ++k) s -= L[i][k] * L[j][k];
      L[i][j] = i == j ? sqrt(max(s, 1e-30)) : s / L[j][j];
    }
    for (int j = i + 1; j < MATRIX_SIZE; ++j) L[i][j] = 0.0;
  }
}

// y = L^-1 e(x); returns |y|^2 = e^T H^-1 e.
float forward(const float L[MATRIX_SIZE][MATRIX_SIZE], float x, out float y[MATRIX_SIZE]) {
  float norm = 0.0, power = 1.0;
  for (int i = 0; i < MATRIX_SIZE; ++i) {
    float s = power;
    for (int k = 0; k < i; ++k) s -= L[i][k] * y[k];
    y[i] = s / L[i][i];
    norm += y[i] * y[i];
    power *= x;
  }
  return norm;
}

float front_fraction(const float normalized[MOMENT_COUNT], float warped_depth) {
  float h[2 * MOMENT_ORDER + 1];
  h[0] = 1.0;
  for (int k = 0; k < MOMENT_COUNT; ++k) h[k + 1] = mix(normalized[k], kBiasVector[k], moment_params.moment_bias);
  float L[MATRIX_SIZE][MATRIX_SIZE];
  factor(h, L);
  float y[MATRIX_SIZE];
  const float own_weight = christoffel(forward(L, warped_depth, y));
  // q = L^-T y = H^-1 e(x_f): the kernel polynomial's coefficients.
  vec2 q[MATRIX_SIZE];
  for (int i = MATRIX_SIZE - 1; i >= 0; --i) {
    float s = y[i];
    for (int k = i + 1; k < MATRIX_SIZE; ++k) s -= L[k][i] * q[k].x;
    q[i] = vec2(s / L[i][i], 0.0);
  }
  vec2 roots[MOMENT_ORDER];
  polynomial_roots(q, roots);
  float lower = 0.0;
  for (int k = 0; k < MOMENT_ORDER; ++k) {
    const float x = roots[k].x;  // real roots: the imaginary part is rounding
    if (x < warped_depth) lower += christoffel(forward(L, x, y));
  }
  return clamp(lower + moment_params.overestimation * own_weight, 0.0, 1.0);
}
#endif
