/* expr.h: a small expression language in x, y, z compiled to stack bytecode, with Lipschitz analysis.
 *
 * Syntax (precedence low to high):
 *   expr    := term (("+" | "-") term)*
 *   term    := unary (("*" | "/") unary)*
 *   unary   := ("-" | "+") unary | power
 *   power   := primary ("^" unary)?          (right associative: 2^3^2 = 2^9)
 *   primary := NUMBER | "x" | "y" | "z" | "pi" | "e"
 *            | FUNC "(" expr ")"              sin cos tan sqrt abs exp log floor
 *            | ("min" | "max") "(" expr "," expr ("," expr)* ")"
 *            | "(" expr ")"
 * Numbers are decimal with an optional fraction and exponent (1, 2.5, 1e-3) and lie within
 * +-EXPR_MAX_NUMBER (docs/scene-language.md §1); hexadecimal, "inf" and "nan" are not numbers.
 *
 * Evaluation follows C's math library (sqrt of a negative is NaN, log(0) is
 * -inf); callers treat non-finite results as "no surface here".
 *
 * Lipschitz analysis: expr_bound() propagates, over an axis-aligned box, an
 * interval for the value and an upper bound G on |grad| of every
 * sub-expression (interval arithmetic on values, chain rule on gradient
 * bounds). It fails, meaning "no bound known here", for floor of a
 * non-constant, tan, division by an interval containing 0, sqrt/log of an
 * interval touching 0, and non-integer powers of non-constants; the renderer
 * then uses its bracketing fallback.
 */
#ifndef LOCUS_EXPR_H
#define LOCUS_EXPR_H

#include <stddef.h>

/* The largest magnitude of a number written in a scene (the float kernels' range). */
#define EXPR_MAX_NUMBER 1e6

/* Length of the unsigned decimal number at s: digits [. digits] or . digits, then an optional
 * exponent e[+-]digits; 0 when s does not start with one. The scene lexer and the expression
 * compiler both read numbers by this one rule. */
size_t expr_decimal_len(const char *s);

/* A compiled expression (opaque). */
typedef struct expr expr_t;

/* Compile src (NUL-terminated). On success returns 0 and *out. On a syntax
 * error returns -1, writes "expected ..." into err (errlen bytes) and the
 * 0-based byte offset of the problem into *errpos. */
int expr_compile(const char *src, expr_t **out, char *err, size_t errlen, size_t *errpos);

/* Free a compiled expression (NULL is fine). */
void expr_free(expr_t *e);

/* Value at (x, y, z), in double. */
double expr_eval(const expr_t *e, double x, double y, double z);

/* Values at 8 points at once, in float: out[k] = e(x[k], y[k], z[k]). */
void expr_eval8(const expr_t *e, const float *x, const float *y, const float *z, float *out);

/* 1 when the expression does not depend on x, y or z. */
int expr_is_constant(const expr_t *e);

/* Interval of values and gradient bound over the box lo..hi (3 values each).
 * Returns 0 and fills *vlo, *vhi, *grad; -1 when no finite bound is known. */
int expr_bound(const expr_t *e, const double lo[3], const double hi[3],
               double *vlo, double *vhi, double *grad);

#endif
