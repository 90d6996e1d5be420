/* expr.c: recursive-descent compiler of x,y,z expressions to stack bytecode; evaluators and interval bounds. */
#include "expr.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
	OP_CONST, OP_X, OP_Y, OP_Z, OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_POW, OP_NEG,
	OP_SIN, OP_COS, OP_TAN, OP_SQRT, OP_ABS, OP_EXP, OP_LOG, OP_FLOOR, OP_MIN, OP_MAX
};

#define EXPR_MAX_OPS 4096
#define EXPR_MAX_DEPTH 64

typedef struct {
	unsigned char op;
	double k;           /* OP_CONST value */
} instr_t;

struct expr {
	instr_t *code;
	size_t n, cap;
	int depth, maxdepth; /* stack depth while compiling / its maximum */
};

typedef struct {
	const char *s;
	size_t pos;
	expr_t *e;
	char *err;
	size_t errlen;
	size_t errpos;
	int failed;
	int nest;
} parser_t;

static const struct { const char *name; unsigned char op; } funcs[] = {
	{"sin", OP_SIN}, {"cos", OP_COS}, {"tan", OP_TAN}, {"sqrt", OP_SQRT}, {"abs", OP_ABS},
	{"exp", OP_EXP}, {"log", OP_LOG}, {"floor", OP_FLOOR}, {"min", OP_MIN}, {"max", OP_MAX},
};

static void fail(parser_t *p, const char *what)
{
	if (p->failed)
		return;
	p->failed = 1;
	p->errpos = p->pos;
	char found[24];
	const char *c = p->s + p->pos;
	if (!*c)
		snprintf(found, sizeof found, "end of expression");
	else {
		size_t n = 0;
		while (c[n] && !isspace((unsigned char)c[n]) && n < 12)
			n++;
		snprintf(found, sizeof found, "'%.*s'", (int)(n ? n : 1), c);
	}
	snprintf(p->err, p->errlen, "expected %s, found %s", what, found);
}

/* Out of memory: said as what happened, not as something expected of the text (the scene
 * reader maps "out of memory" to its exit 70 path). */
static void fail_oom(parser_t *p)
{
	if (p->failed)
		return;
	p->failed = 1;
	p->errpos = p->pos;
	snprintf(p->err, p->errlen, "out of memory compiling the expression");
}

static void emit(parser_t *p, unsigned char op, double k)
{
	expr_t *e = p->e;
	if (p->failed)
		return;
	if (e->n == e->cap) {
		size_t cap = e->cap ? e->cap * 2 : 16;
		if (cap > EXPR_MAX_OPS) {
			fail(p, "a shorter expression (at most 4096 operations)");
			return;
		}
		instr_t *c = realloc(e->code, cap * sizeof *c);
		if (!c) {
			fail_oom(p);
			return;
		}
		e->code = c;
		e->cap = cap;
	}
	e->code[e->n].op = op;
	e->code[e->n].k = k;
	e->n++;
	if (op <= OP_Z)
		e->depth++;
	else if (op >= OP_ADD && op <= OP_POW)
		e->depth--;
	else if (op == OP_MIN || op == OP_MAX)
		e->depth--;
	if (e->depth > e->maxdepth)
		e->maxdepth = e->depth;
	if (e->maxdepth > EXPR_MAX_DEPTH)
		fail(p, "a less deeply nested expression");
}

static void skip(parser_t *p)
{
	while (isspace((unsigned char)p->s[p->pos]))
		p->pos++;
}

static int accept(parser_t *p, char c)
{
	skip(p);
	if (p->s[p->pos] == c) {
		p->pos++;
		return 1;
	}
	return 0;
}

static void parse_expr(parser_t *p);
static void parse_unary(parser_t *p);

size_t expr_decimal_len(const char *s)
{
	size_t n = 0, digits = 0;
	while (isdigit((unsigned char)s[n]))
		n++, digits++;
	if (s[n] == '.') {
		n++;
		while (isdigit((unsigned char)s[n]))
			n++, digits++;
	}
	if (!digits)
		return 0;
	if (s[n] == 'e' || s[n] == 'E') {
		size_t k = n + 1;
		if (s[k] == '+' || s[k] == '-')
			k++;
		if (isdigit((unsigned char)s[k])) {
			while (isdigit((unsigned char)s[k]))
				k++;
			n = k;
		}
	}
	return n;
}

static void parse_primary(parser_t *p)
{
	skip(p);
	const char *c = p->s + p->pos;
	if (isdigit((unsigned char)*c) || (*c == '.' && isdigit((unsigned char)c[1]))) {
		size_t n = expr_decimal_len(c);
		char buf[64];
		if (n >= sizeof buf || isalnum((unsigned char)c[n]) || c[n] == '.' || c[n] == '_') {
			fail(p, "a decimal number (digits, a fraction, an exponent)");
			return;
		}
		memcpy(buf, c, n);
		buf[n] = 0;
		double v = strtod(buf, NULL);
		if (!isfinite(v) || fabs(v) > EXPR_MAX_NUMBER) {
			fail(p, "a number between -1e6 and 1e6 (the float kernels' range)");
			return;
		}
		p->pos += n;
		emit(p, OP_CONST, v);
		return;
	}
	if (isalpha((unsigned char)*c)) {
		size_t n = 0;
		while (isalnum((unsigned char)c[n]) || c[n] == '_')
			n++;
		if (n == 1 && (*c == 'x' || *c == 'y' || *c == 'z')) {
			p->pos += 1;
			emit(p, (unsigned char)(OP_X + (*c - 'x')), 0);
			return;
		}
		if (n == 2 && !strncmp(c, "pi", 2)) {
			p->pos += 2;
			emit(p, OP_CONST, 3.14159265358979323846);
			return;
		}
		if (n == 1 && *c == 'e') {
			p->pos += 1;
			emit(p, OP_CONST, 2.71828182845904523536);
			return;
		}
		for (size_t i = 0; i < sizeof funcs / sizeof funcs[0]; i++) {
			if (strlen(funcs[i].name) != n || strncmp(funcs[i].name, c, n))
				continue;
			p->pos += n;
			if (!accept(p, '(')) {
				fail(p, "'(' after a function name");
				return;
			}
			parse_expr(p);
			if (funcs[i].op == OP_MIN || funcs[i].op == OP_MAX) {
				if (!accept(p, ',')) {
					fail(p, "',' and a second argument");
					return;
				}
				do {
					parse_expr(p);
					emit(p, funcs[i].op, 0);
				} while (!p->failed && accept(p, ','));
			} else {
				emit(p, funcs[i].op, 0);
			}
			if (!accept(p, ')'))
				fail(p, "')' closing the function call");
			return;
		}
		fail(p, "a number, x, y, z, pi, e, a function (sin cos tan sqrt abs exp log floor min max) or '('");
		return;
	}
	if (accept(p, '(')) {
		if (++p->nest > 200) {
			fail(p, "fewer nested parentheses");
			return;
		}
		parse_expr(p);
		p->nest--;
		if (!accept(p, ')'))
			fail(p, "')'");
		return;
	}
	fail(p, "a number, x, y, z, pi, e, a function or '('");
}

static void parse_power(parser_t *p)
{
	parse_primary(p);
	if (!p->failed && accept(p, '^')) {
		parse_unary(p);
		emit(p, OP_POW, 0);
	}
}

static void parse_unary(parser_t *p)
{
	if (++p->nest > 200) {
		fail(p, "fewer nested operators");
		return;
	}
	if (accept(p, '-')) {
		parse_unary(p);
		emit(p, OP_NEG, 0);
	} else if (accept(p, '+')) {
		parse_unary(p);
	} else {
		parse_power(p);
	}
	p->nest--;
}

static void parse_term(parser_t *p)
{
	parse_unary(p);
	while (!p->failed) {
		if (accept(p, '*')) {
			parse_unary(p);
			emit(p, OP_MUL, 0);
		} else if (accept(p, '/')) {
			parse_unary(p);
			emit(p, OP_DIV, 0);
		} else
			break;
	}
}

static void parse_expr(parser_t *p)
{
	parse_term(p);
	while (!p->failed) {
		if (accept(p, '+')) {
			parse_term(p);
			emit(p, OP_ADD, 0);
		} else if (accept(p, '-')) {
			parse_term(p);
			emit(p, OP_SUB, 0);
		} else
			break;
	}
}

int expr_compile(const char *src, expr_t **out, char *err, size_t errlen, size_t *errpos)
{
	char dummy[8];
	parser_t p = {0};
	p.s = src;
	p.err = err ? err : dummy;
	p.errlen = err ? errlen : sizeof dummy;
	*out = NULL;
	p.e = calloc(1, sizeof *p.e);
	if (!p.e) {
		snprintf(p.err, p.errlen, "out of memory");
		if (errpos)
			*errpos = 0;
		return -1;
	}
	parse_expr(&p);
	skip(&p);
	if (!p.failed && p.s[p.pos])
		fail(&p, "an operator or the end of the expression");
	if (p.failed) {
		if (errpos)
			*errpos = p.errpos;
		expr_free(p.e);
		return -1;
	}
	*out = p.e;
	return 0;
}

void expr_free(expr_t *e)
{
	if (!e)
		return;
	free(e->code);
	free(e);
}

int expr_is_constant(const expr_t *e)
{
	for (size_t i = 0; i < e->n; i++)
		if (e->code[i].op >= OP_X && e->code[i].op <= OP_Z)
			return 0;
	return 1;
}

static double apply1(int op, double a)
{
	switch (op) {
	case OP_NEG: return -a;
	case OP_SIN: return sin(a);
	case OP_COS: return cos(a);
	case OP_TAN: return tan(a);
	case OP_SQRT: return sqrt(a);
	case OP_ABS: return fabs(a);
	case OP_EXP: return exp(a);
	case OP_LOG: return log(a);
	default: return floor(a);
	}
}

static double apply2(int op, double a, double b)
{
	switch (op) {
	case OP_ADD: return a + b;
	case OP_SUB: return a - b;
	case OP_MUL: return a * b;
	case OP_DIV: return a / b;
	case OP_POW: return pow(a, b);
	case OP_MIN: return a < b ? a : b;
	default: return a > b ? a : b;
	}
}

double expr_eval(const expr_t *e, double x, double y, double z)
{
	double st[EXPR_MAX_DEPTH + 1];
	int sp = 0;
	for (size_t i = 0; i < e->n; i++) {
		int op = e->code[i].op;
		switch (op) {
		case OP_CONST: st[sp++] = e->code[i].k; break;
		case OP_X: st[sp++] = x; break;
		case OP_Y: st[sp++] = y; break;
		case OP_Z: st[sp++] = z; break;
		case OP_ADD: case OP_SUB: case OP_MUL: case OP_DIV: case OP_POW: case OP_MIN: case OP_MAX:
			sp--;
			st[sp - 1] = apply2(op, st[sp - 1], st[sp]);
			break;
		default:
			st[sp - 1] = apply1(op, st[sp - 1]);
		}
	}
	return sp ? st[0] : NAN;
}

void expr_eval8(const expr_t *e, const float *x, const float *y, const float *z, float *out)
{
	float st[EXPR_MAX_DEPTH + 1][8];
	int sp = 0;
	for (size_t i = 0; i < e->n; i++) {
		int op = e->code[i].op;
		float *a = st[sp > 0 ? sp - 1 : 0], *b = st[sp];
		switch (op) {
		case OP_CONST: for (int k = 0; k < 8; k++) b[k] = (float)e->code[i].k; sp++; break;
		case OP_X: memcpy(b, x, sizeof st[0]); sp++; break;
		case OP_Y: memcpy(b, y, sizeof st[0]); sp++; break;
		case OP_Z: memcpy(b, z, sizeof st[0]); sp++; break;
		case OP_ADD: b = a; a = st[sp - 2]; for (int k = 0; k < 8; k++) a[k] += b[k]; sp--; break;
		case OP_SUB: b = a; a = st[sp - 2]; for (int k = 0; k < 8; k++) a[k] -= b[k]; sp--; break;
		case OP_MUL: b = a; a = st[sp - 2]; for (int k = 0; k < 8; k++) a[k] *= b[k]; sp--; break;
		case OP_DIV: b = a; a = st[sp - 2]; for (int k = 0; k < 8; k++) a[k] /= b[k]; sp--; break;
		case OP_MIN: b = a; a = st[sp - 2]; for (int k = 0; k < 8; k++) a[k] = fminf(a[k], b[k]); sp--; break;
		case OP_MAX: b = a; a = st[sp - 2]; for (int k = 0; k < 8; k++) a[k] = fmaxf(a[k], b[k]); sp--; break;
		case OP_POW: b = a; a = st[sp - 2]; for (int k = 0; k < 8; k++) a[k] = powf(a[k], b[k]); sp--; break;
		case OP_NEG: for (int k = 0; k < 8; k++) a[k] = -a[k]; break;
		case OP_SQRT: for (int k = 0; k < 8; k++) a[k] = sqrtf(a[k]); break;
		case OP_ABS: for (int k = 0; k < 8; k++) a[k] = fabsf(a[k]); break;
		case OP_SIN: for (int k = 0; k < 8; k++) a[k] = sinf(a[k]); break;
		case OP_COS: for (int k = 0; k < 8; k++) a[k] = cosf(a[k]); break;
		case OP_TAN: for (int k = 0; k < 8; k++) a[k] = tanf(a[k]); break;
		case OP_EXP: for (int k = 0; k < 8; k++) a[k] = expf(a[k]); break;
		case OP_LOG: for (int k = 0; k < 8; k++) a[k] = logf(a[k]); break;
		default: for (int k = 0; k < 8; k++) a[k] = floorf(a[k]); break;
		}
	}
	memcpy(out, st[0], sizeof st[0]);
}

/* ---- interval + gradient-bound analysis ---- */

typedef struct {
	double lo, hi, g;
} ival_t;

static double amax(ival_t a) { return fmax(fabs(a.lo), fabs(a.hi)); }
static double amin(ival_t a) { return (a.lo <= 0 && a.hi >= 0) ? 0 : fmin(fabs(a.lo), fabs(a.hi)); }

static int bound_op(int op, double k, ival_t *a, ival_t b)
{
	ival_t r = {0, 0, 0};
	double c[4];
	switch (op) {
	case OP_ADD: r.lo = a->lo + b.lo; r.hi = a->hi + b.hi; r.g = a->g + b.g; break;
	case OP_SUB: r.lo = a->lo - b.hi; r.hi = a->hi - b.lo; r.g = a->g + b.g; break;
	case OP_MUL:
		c[0] = a->lo * b.lo; c[1] = a->lo * b.hi; c[2] = a->hi * b.lo; c[3] = a->hi * b.hi;
		r.lo = fmin(fmin(c[0], c[1]), fmin(c[2], c[3]));
		r.hi = fmax(fmax(c[0], c[1]), fmax(c[2], c[3]));
		r.g = amax(*a) * b.g + amax(b) * a->g;
		break;
	case OP_DIV:
		if (b.lo <= 0 && b.hi >= 0)
			return -1;
		c[0] = a->lo / b.lo; c[1] = a->lo / b.hi; c[2] = a->hi / b.lo; c[3] = a->hi / b.hi;
		r.lo = fmin(fmin(c[0], c[1]), fmin(c[2], c[3]));
		r.hi = fmax(fmax(c[0], c[1]), fmax(c[2], c[3]));
		r.g = a->g / amin(b) + amax(*a) * b.g / (amin(b) * amin(b));
		break;
	case OP_MIN: r.lo = fmin(a->lo, b.lo); r.hi = fmin(a->hi, b.hi); r.g = fmax(a->g, b.g); break;
	case OP_MAX: r.lo = fmax(a->lo, b.lo); r.hi = fmax(a->hi, b.hi); r.g = fmax(a->g, b.g); break;
	case OP_POW:
		if (b.g != 0 || b.lo != b.hi)
			return -1;
		if (b.lo != floor(b.lo) || fabs(b.lo) > 64) {
			if (a->g != 0)
				return -1;
			r.lo = r.hi = pow(a->lo, b.lo);
			break;
		}
		{
			int n = (int)b.lo;
			if (n < 0 && a->lo <= 0 && a->hi >= 0)
				return -1;
			double p1 = pow(a->lo, n), p2 = pow(a->hi, n);
			r.lo = fmin(p1, p2);
			r.hi = fmax(p1, p2);
			if (n % 2 == 0 && n > 0 && a->lo < 0 && a->hi > 0)
				r.lo = 0;
			r.g = n == 0 ? 0 : fabs((double)n) * (n > 0 ? pow(amax(*a), n - 1) : pow(amin(*a), n - 1)) * a->g;
		}
		break;
	case OP_NEG: r.lo = -a->hi; r.hi = -a->lo; r.g = a->g; break;
	case OP_SIN: case OP_COS:
		r.g = a->g;
		if (a->hi - a->lo < 1e-12) {
			r.lo = r.hi = op == OP_SIN ? sin(a->lo) : cos(a->lo);
		} else {
			r.lo = -1;
			r.hi = 1;
		}
		break;
	case OP_TAN:
		if (a->g != 0)
			return -1;
		r.lo = r.hi = tan(a->lo);
		break;
	case OP_SQRT:
		if (a->lo < 0)
			return -1;
		r.lo = sqrt(a->lo);
		r.hi = sqrt(a->hi);
		if (a->g != 0) {
			if (a->lo <= 0)
				return -1;
			r.g = a->g / (2 * r.lo);
		}
		break;
	case OP_ABS:
		r.lo = amin(*a); r.hi = amax(*a); r.g = a->g; break;
	case OP_EXP:
		r.lo = exp(a->lo); r.hi = exp(a->hi); r.g = a->g * r.hi; break;
	case OP_LOG:
		if (a->lo <= 0)
			return -1;
		r.lo = log(a->lo); r.hi = log(a->hi); r.g = a->g / a->lo; break;
	case OP_FLOOR:
		if (a->g != 0)
			return -1;
		r.lo = r.hi = floor(a->lo);
		break;
	default:
		(void)k;
		return -1;
	}
	if (!isfinite(r.lo) || !isfinite(r.hi) || !isfinite(r.g))
		return -1;
	*a = r;
	return 0;
}

int expr_bound(const expr_t *e, const double lo[3], const double hi[3],
               double *vlo, double *vhi, double *grad)
{
	ival_t st[EXPR_MAX_DEPTH + 1];
	int sp = 0;
	for (size_t i = 0; i < e->n; i++) {
		int op = e->code[i].op;
		if (op == OP_CONST) {
			st[sp].lo = st[sp].hi = e->code[i].k;
			st[sp++].g = 0;
		} else if (op <= OP_Z) {
			st[sp].lo = lo[op - OP_X];
			st[sp].hi = hi[op - OP_X];
			st[sp++].g = 1;
		} else if (op >= OP_ADD && (op <= OP_POW || op == OP_MIN || op == OP_MAX)) {
			sp--;
			if (bound_op(op, 0, &st[sp - 1], st[sp]) < 0)
				return -1;
		} else {
			ival_t none = {0, 0, 0};
			if (bound_op(op, 0, &st[sp - 1], none) < 0)
				return -1;
		}
	}
	if (sp != 1)
		return -1;
	*vlo = st[0].lo;
	*vhi = st[0].hi;
	*grad = st[0].g;
	return 0;
}
