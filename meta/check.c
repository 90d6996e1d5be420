/* check.c: structural and value validation of statements (spec sections 4 and 6), shared by reader and writer. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "meta_int.h"

#define FAIL(code, w, ...) do { *where = (w); meta_fmt(msg, n, __VA_ARGS__); return (code); } while (0)

/* A value as §6 shows it: the canonical text form of §2, quoted by the caller. */
static const char *fx(meta_fix_t v, char *buf)
{
	buf[meta_fix_format(v, buf)] = 0;
	return buf;
}

static int is_path_op(meta_op_t op)
{
	return op == META_MOVE || op == META_DRAW || op == META_ARC || op == META_CIRCLE ||
	       op == META_CLOSE || op == META_END;
}

/* Every 'f' operand must lie within the number range (the writer may be handed anything). */
static int check_range(const meta_cmd_t *cmd, int *where, char *msg, size_t n)
{
	char vb[24];
	const char *sig = meta_ops[cmd->op].sig;
	int i, fi = 0;
	for (i = 0; sig[i]; i++) {
		if (sig[i] != 'f')
			continue;
		if (cmd->f[fi] > META_MAX_COORD || cmd->f[fi] < -META_MAX_COORD)
			FAIL(META_ELIMIT, i, "expected a number from -1000000 to 1000000 for '%s', found '%s'",
			     meta_ops[cmd->op].kw, fx(cmd->f[fi], vb));
		fi++;
	}
	return 0;
}

static int check_string(const meta_cmd_t *cmd, int *where, char *msg, size_t n)
{
	size_t i;
	int comment = cmd->op == META_COMMENT;
	int arg = comment ? 0 : 4;
	if (cmd->len && !cmd->str)
		FAIL(META_EARG, arg, "expected a string for '%s', found a null pointer", meta_ops[cmd->op].kw);
	if (cmd->len > META_MAX_STRING)
		FAIL(META_ELIMIT, arg, "expected at most %d bytes in a %s, found %zu bytes", META_MAX_STRING,
		     comment ? "comment" : "string", cmd->len);
	for (i = 0; i < cmd->len; i++) {
		unsigned char c = (unsigned char)cmd->str[i];
		if (c == 0 || (comment && (c == '\n' || c == '\r')))
			FAIL(META_ESYNTAX, arg, "expected no %s byte in a %s, found 0x%02x at index %zu",
			     c ? "line-break" : "NUL", comment ? "comment" : "string", c, i);
	}
	return 0;
}

static int check_values(const meta_cmd_t *cmd, int *where, char *msg, size_t n)
{
	const char *kw = meta_ops[cmd->op].kw;
	size_t i;
	char vb[24];
	int rc = check_range(cmd, where, msg, n);
	if (rc)
		return rc;
	switch (cmd->op) {
	case META_PAGE:
		for (i = 0; i < 2; i++)
			if (cmd->u[i] < 1 || cmd->u[i] > META_MAX_DIM)
				FAIL(META_ELIMIT, (int)i, "expected a page %s from 1 to %d, found '%u'",
				     i ? "height" : "width", META_MAX_DIM, cmd->u[i]);
		break;
	case META_SIZE:
		for (i = 0; i < 2; i++)
			if (cmd->f[i] <= 0)
				FAIL(META_ESYNTAX, (int)i, "expected a positive physical %s for 'size', found '%s'",
				     i ? "height" : "width", fx(cmd->f[i], vb));
		break;
	case META_CLEAR: case META_COLOUR:
		if (cmd->rgb > 0xffffff)
			FAIL(META_EARG, 0, "expected a colour 0xRRGGBB for '%s', found 0x%x", kw, cmd->rgb);
		break;
	case META_WIDTH:
		if (cmd->f[0] < 0)
			FAIL(META_ESYNTAX, 0, "expected a width >= 0, found '%s'", fx(cmd->f[0], vb));
		break;
	case META_MITER_LIMIT:
		if (cmd->f[0] < META_FIX_ONE)
			FAIL(META_ESYNTAX, 0, "expected a miter limit >= 1, found '%s'", fx(cmd->f[0], vb));
		break;
	case META_DASH:
		if (cmd->nlist > META_MAX_DASH)
			FAIL(META_ELIMIT, 0, "expected at most %d dash lengths, found %zu lengths", META_MAX_DASH, cmd->nlist);
		if (cmd->nlist && !cmd->list)
			FAIL(META_EARG, 0, "expected a dash list, found a null pointer");
		for (i = 0; i < cmd->nlist; i++)
			if (cmd->list[i] <= 0 || cmd->list[i] > META_MAX_COORD)
				FAIL(META_ESYNTAX, 0, "expected dash lengths > 0 and <= 1000000, found '%s' (entry %zu)",
				     fx(cmd->list[i], vb), i + 1);
		break;
	case META_CAP: case META_JOIN: case META_FILL_RULE:
		if (cmd->k < 0 || cmd->k >= meta_ops[cmd->op].nwords)
			FAIL(META_ESYNTAX, 0, "expected a keyword index below %d for '%s', found '%d'",
			     meta_ops[cmd->op].nwords, kw, cmd->k);
		break;
	case META_ARC: case META_CIRCLE:
		if (cmd->f[2] <= 0)
			FAIL(META_ESYNTAX, 2, "expected a radius > 0 for '%s', found '%s'", kw, fx(cmd->f[2], vb));
		if (cmd->op == META_ARC && (cmd->f[4] > 360 * META_FIX_ONE || cmd->f[4] < -360 * META_FIX_ONE))
			FAIL(META_ESYNTAX, 4, "expected a sweep from -360 to 360 for 'arc', found '%s'",
			     fx(cmd->f[4], vb));
		break;
	case META_TEXT:
		if (cmd->f[2] < 0)
			FAIL(META_ESYNTAX, 2, "expected a text size >= 0, found '%s'", fx(cmd->f[2], vb));
		return check_string(cmd, where, msg, n);
	case META_COMMENT:
		return check_string(cmd, where, msg, n);
	case META_SPAN:
		for (i = 0; i < 3; i++)
			if (cmd->u[i] > META_MAX_DIM)
				FAIL(META_ELIMIT, (int)i, "expected a span %s from 0 to %d, found '%u'",
				     i == 0 ? "x" : i == 1 ? "y" : "length", META_MAX_DIM, cmd->u[i]);
		if (cmd->u[2] < 1)
			FAIL(META_ESYNTAX, 2, "expected a span length >= 1, found '0'");
		if (cmd->rgb > 0xffffff)
			FAIL(META_EARG, 3, "expected a colour 0xRRGGBB for 'span', found 0x%x", cmd->rgb);
		break;
	case META_IMAGE:
		for (i = 0; i < 4; i++)
			if (cmd->u[i] > META_MAX_DIM || (i >= 2 && cmd->u[i] < 1))
				FAIL(META_ELIMIT, (int)i, "expected an image %s from %d to %d, found '%u'",
				     i == 0 ? "x" : i == 1 ? "y" : i == 2 ? "width" : "height",
				     i >= 2, META_MAX_DIM, cmd->u[i]);
		break;
	default:
		break;
	}
	return 0;
}

static int check_row(meta_check_t *c, const meta_cmd_t *cmd, int *where, char *msg, size_t n)
{
	uint64_t sum = 0;
	size_t i;
	if (cmd->nruns && !cmd->runs)
		FAIL(META_EARG, 0, "expected a run list, found a null pointer");
	for (i = 0; i < cmd->nruns; i++) {
		if (cmd->runs[i].count < 1)
			FAIL(META_ESYNTAX, 0, "expected run counts >= 1, found 0 (run %zu)", i + 1);
		if (cmd->runs[i].rgb > 0xffffff)
			FAIL(META_EARG, 0, "expected run colours 0xRRGGBB, found 0x%x", cmd->runs[i].rgb);
		sum += cmd->runs[i].count;
	}
	if (sum != c->image_w)
		FAIL(META_ESYNTAX, -1, "expected runs adding up to the image width %u, found %llu",
		     c->image_w, (unsigned long long)sum);
	return 0;
}

int meta_circle_chords(int64_t r)
{
	double rp = (double)r / 1000.0;
	if (!(rp > 0.25))
		return 8;
	double m = ceil(2.0 * M_PI / acos(1.0 - 0.25 / rp));
	if (!(m < 1e7))
		m = 1e7;
	return m < 8 ? 8 : (int)m;
}

int64_t meta_arc_chords(int64_t r, int64_t sweep)
{
	int64_t m = meta_circle_chords(r), as = sweep < 0 ? -sweep : sweep;
	int64_t k = (as * m + 359999) / 360000;
	return k < 1 ? 1 : k;
}

/* Points a path statement adds once flattened (§6): move 1, draw 1, arc N + 1, circle M, and
 * one more for a draw or arc that begins a new subpath at the start of a closed one. */
static uint64_t flat_points(const meta_check_t *c, const meta_cmd_t *cmd)
{
	switch (cmd->op) {
	case META_MOVE: return 1;
	case META_DRAW: return 1 + (uint64_t)c->closed;
	case META_ARC: return (uint64_t)meta_arc_chords(cmd->f[2], cmd->f[4]) + 1 + (uint64_t)(c->has_point && c->closed);
	case META_CIRCLE: return (uint64_t)meta_circle_chords(cmd->f[2]);
	default: return 0;
	}
}

int meta_check_cmd(meta_check_t *c, const meta_cmd_t *cmd, int *where, char *msg, size_t n)
{
	meta_op_t op = cmd->op;
	const char *kw;
	int rc;
	if ((op == META_DRAW || op == META_MOVE) && c->in_path && (c->has_point || op == META_MOVE) &&
	    c->path_points < META_MAX_PATH_POINTS && c->flat + 2 <= META_MAX_FLAT_POINTS &&
	    cmd->f[0] <= META_MAX_COORD && cmd->f[0] >= -META_MAX_COORD &&
	    cmd->f[1] <= META_MAX_COORD && cmd->f[1] >= -META_MAX_COORD) {
		c->path_points++; /* fast path of the most common statements */
		c->flat += op == META_DRAW && c->closed ? 2 : 1;
		c->has_point = 1;
		c->closed = 0;
		return 0;
	}
	if ((unsigned)op >= META_OP_COUNT)
		FAIL(META_EARG, -1, "expected a statement kind, found %d", (int)op);
	kw = meta_ops[op].kw;
	if (op == META_COMMENT)
		return check_values(cmd, where, msg, n);
	if (!c->in_page && op != META_PAGE)
		FAIL(META_ESTATE, -1, "expected 'page' before '%s'", kw);
	if (c->rows_left && op != META_ROW)
		FAIL(META_ESTATE, -1, "expected 'row' (%u more for the image), found '%s'", c->rows_left, kw);
	if (c->in_path && !is_path_op(op))
		FAIL(META_ESTATE, -1, "expected a path statement or 'end', found '%s'%s", kw,
		     op <= META_MITER_LIMIT && op >= META_COLOUR ? " (state cannot change inside a path)" : "");
	rc = check_values(cmd, where, msg, n);
	if (rc)
		return rc;
	switch (op) {
	case META_PAGE:
		if (c->in_page)
			FAIL(META_ESTATE, -1, "expected 'end-page' before 'page'");
		c->in_page = c->any_page = c->first = 1;
		return 0;
	case META_SIZE:
		if (!c->first)
			FAIL(META_ESTATE, -1, "expected 'size' only directly after 'page', found it later");
		break;
	case META_END_PAGE:
		c->in_page = 0;
		break;
	case META_STROKE: case META_FILL:
		c->in_path = 1;
		c->has_point = 0;
		c->closed = 0;
		c->path_points = 0;
		c->flat = 0;
		break;
	case META_MOVE: case META_DRAW: case META_ARC: case META_CIRCLE: case META_CLOSE: case META_END:
		if (!c->in_path)
			FAIL(META_ESTATE, -1, "expected 'stroke' or 'fill' before '%s'", kw);
		if ((op == META_DRAW || op == META_CLOSE) && !c->has_point)
			FAIL(META_ESTATE, -1, "expected 'move' before '%s' (no current point)", kw);
		if (op == META_END) {
			c->in_path = 0;
			break;
		}
		if (op != META_CLOSE && ++c->path_points > META_MAX_PATH_POINTS)
			FAIL(META_ELIMIT, -1, "expected at most %d points in one path, found more",
			     META_MAX_PATH_POINTS);
		if ((c->flat += flat_points(c, cmd)) > META_MAX_FLAT_POINTS)
			FAIL(META_ELIMIT, -1, "expected at most %d points in one path once its arcs and "
			     "circles are flattened, found more", META_MAX_FLAT_POINTS);
		c->closed = op == META_CLOSE;
		c->has_point = op != META_CIRCLE;
		break;
	case META_IMAGE:
		c->rows_left = cmd->u[3];
		c->image_w = cmd->u[2];
		break;
	case META_ROW:
		if (!c->rows_left)
			FAIL(META_ESTATE, -1, "expected 'image' before 'row'");
		rc = check_row(c, cmd, where, msg, n);
		if (rc)
			return rc;
		c->rows_left--;
		break;
	default:
		break;
	}
	c->first = 0;
	return 0;
}

int meta_check_eof(const meta_check_t *c, char *msg, size_t n)
{
	if (c->in_path)
		meta_fmt(msg, n, "expected 'end' of the path, found end of file (truncated?)");
	else if (c->rows_left)
		meta_fmt(msg, n, "expected %u more 'row' statements, found end of file (truncated?)", c->rows_left);
	else if (c->in_page)
		meta_fmt(msg, n, "expected 'end-page', found end of file (unterminated page)");
	else if (!c->any_page)
		meta_fmt(msg, n, "expected 'page', found end of file (a file holds at least one page)");
	else
		return 0;
	return META_ESTATE;
}
