/* test_expr.c: the expression compiler: values, precedence, errors with positions, interval/gradient bounds. */
#include "unit.h"
#include "expr.h"

#include <math.h>
#include <stdlib.h>

static double ev(const char *s, double x, double y, double z)
{
	expr_t *e;
	char err[128];
	size_t pos;
	if (expr_compile(s, &e, err, sizeof err, &pos) < 0)
		return NAN;
	double v = expr_eval(e, x, y, z);
	expr_free(e);
	return v;
}

static int fails_at(const char *s, size_t want, const char *text)
{
	expr_t *e;
	char err[128];
	size_t pos = 999;
	if (expr_compile(s, &e, err, sizeof err, &pos) == 0) {
		expr_free(e);
		return 0;
	}
	if (pos != want)
		printf("# '%s': error at %zu (%s), wanted %zu\n", s, pos, err, want);
	return pos == want && strstr(err, text) != NULL;
}

int main(void)
{
	CHECK(ev("1 + 2 * 3", 0, 0, 0) == 7, "precedence of * over +");
	CHECK(ev("2 ^ 3 ^ 2", 0, 0, 0) == 512, "^ is right associative");
	CHECK(ev("-2 ^ 2", 0, 0, 0) == -4, "unary minus binds looser than ^");
	CHECK(ev("(1 + 2) * 3", 0, 0, 0) == 9, "parentheses");
	CHECK(ev("x + 2*y - z/4", 1, 2, 8) == 3, "variables x y z");
	CHECK(fabs(ev("sin(pi/2) + cos(0) + sqrt(16) + abs(-3)", 0, 0, 0) - 9) < 1e-12, "sin cos sqrt abs pi");
	CHECK(fabs(ev("exp(log(5)) + floor(2.7) + tan(0)", 0, 0, 0) - 7) < 1e-12, "exp log floor tan");
	CHECK(ev("min(3, x, 2) + max(y, 1)", 5, 7, 0) == 9, "n-ary min, max");
	CHECK(ev("1e-3 * 1000 + .5", 0, 0, 0) == 1.5, "number forms");
	CHECK(ev("e", 0, 0, 0) == exp(1.0), "the constant e");
	CHECK(isnan(ev("sqrt(x)", -1, 0, 0)), "sqrt of a negative is NaN, not an error");

	CHECK(fails_at("1 +", 3, "expected a number"), "missing operand at the end");
	CHECK(fails_at("2 * (x + 1", 10, "')'"), "unclosed parenthesis");
	CHECK(fails_at("foo(2)", 0, "expected a number, x"), "unknown name");
	CHECK(fails_at("min(1)", 5, "','"), "min needs two arguments");
	CHECK(fails_at("1 2", 2, "an operator"), "two numbers in a row");
	CHECK(fails_at("", 0, "end of expression"), "empty expression");
	CHECK(fails_at("sin 2", 4, "'('"), "function without parentheses");

	/* 8-wide evaluation agrees with the scalar one */
	{
		expr_t *e;
		char err[64];
		size_t pos;
		CHECK(expr_compile("2 + 0.5*sin(3*x) - y*z + max(x, 0.1)^2", &e, err, sizeof err, &pos) == 0, "compile for eval8");
		float x[8], y[8], z[8], out[8];
		for (int k = 0; k < 8; k++) {
			x[k] = -1 + 0.3f * k;
			y[k] = 0.5f * k;
			z[k] = 1 - 0.1f * k;
		}
		expr_eval8(e, x, y, z, out);
		double worst = 0;
		for (int k = 0; k < 8; k++)
			worst = fmax(worst, fabs(out[k] - expr_eval(e, x[k], y[k], z[k])));
		CHECK(worst < 1e-5, "eval8 matches eval (worst %g)", worst);
		CHECK(!expr_is_constant(e), "depends on x");
		expr_free(e);
		CHECK(expr_compile("2*pi + 1", &e, err, sizeof err, &pos) == 0 && expr_is_constant(e), "constant expression");
		expr_free(e);
	}

	/* bounds: values inside the interval and slopes below the gradient bound, on random samples */
	{
		const char *cases[] = {"2 + x/2", "0.3*sin(4*x) + 0.2*cos(3*y*z)", "x*y - z^2", "sqrt(x^2 + y^2 + 1)",
		                       "exp(0.2*x) - log(y + 3)", "min(x, y) + max(z, 0)^3", "abs(x - y)/(2 + z)"};
		srand(7);
		for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
			expr_t *e;
			char err[64];
			size_t pos;
			expr_compile(cases[c], &e, err, sizeof err, &pos);
			double lo[3] = {-1, -1.5, -0.5}, hi[3] = {1.5, 1, 1}, vlo, vhi, g;
			int ok = expr_bound(e, lo, hi, &vlo, &vhi, &g) == 0, bad = 0;
			for (int i = 0; ok && i < 20000; i++) {
				double p[3], q[3];
				for (int j = 0; j < 3; j++) {
					p[j] = lo[j] + (hi[j] - lo[j]) * rand() / (double)RAND_MAX;
					q[j] = lo[j] + (hi[j] - lo[j]) * rand() / (double)RAND_MAX;
				}
				double a = expr_eval(e, p[0], p[1], p[2]), b = expr_eval(e, q[0], q[1], q[2]);
				double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
				if (a < vlo - 1e-12 || a > vhi + 1e-12 || fabs(a - b) > g * d + 1e-12)
					bad++;
			}
			CHECK(ok && bad == 0, "bound of '%s' holds on 20000 samples (G = %g)", cases[c], g);
			expr_free(e);
		}
		const char *unbounded[] = {"floor(x)", "tan(x)", "1/x", "sqrt(x)", "log(y)", "x^0.5"};
		for (size_t c = 0; c < sizeof unbounded / sizeof unbounded[0]; c++) {
			expr_t *e;
			char err[64];
			size_t pos;
			expr_compile(unbounded[c], &e, err, sizeof err, &pos);
			double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1}, vlo, vhi, g;
			CHECK(expr_bound(e, lo, hi, &vlo, &vhi, &g) < 0, "'%s' has no bound over a box around 0", unbounded[c]);
			expr_free(e);
		}
	}
	return UNIT_DONE();
}
