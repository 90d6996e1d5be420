/* msq.c: internals shared by the grid tracers (contour, Voronoi boundaries): the marching-squares exit table and the error message slot. */
#include "msq.h"

#include <stdarg.h>
#include <stdio.h>

/* Derived from the rule in msq.h (tests/unit/test_contour.c derives it again and compares). */
const signed char msq_exit[2][16][4] = {
	{ /* s = 0 */
		{-1, -1, -1, -1}, /*  0 */
		{ 3, -1, -1, -1}, /*  1 */
		{-1,  0, -1, -1}, /*  2 */
		{-1,  3, -1, -1}, /*  3 */
		{-1, -1,  1, -1}, /*  4 */
		{ 3, -1,  1, -1}, /*  5 */
		{-1, -1,  0, -1}, /*  6 */
		{-1, -1,  3, -1}, /*  7 */
		{-1, -1, -1,  2}, /*  8 */
		{ 2, -1, -1, -1}, /*  9 */
		{-1,  0, -1,  2}, /* 10 */
		{-1,  2, -1, -1}, /* 11 */
		{-1, -1, -1,  1}, /* 12 */
		{ 1, -1, -1, -1}, /* 13 */
		{-1, -1, -1,  0}, /* 14 */
		{-1, -1, -1, -1}, /* 15 */
	},
	{ /* s = 1 */
		{-1, -1, -1, -1}, /*  0 */
		{ 3, -1, -1, -1}, /*  1 */
		{-1,  0, -1, -1}, /*  2 */
		{-1,  3, -1, -1}, /*  3 */
		{-1, -1,  1, -1}, /*  4 */
		{ 1, -1,  3, -1}, /*  5 */
		{-1, -1,  0, -1}, /*  6 */
		{-1, -1,  3, -1}, /*  7 */
		{-1, -1, -1,  2}, /*  8 */
		{ 2, -1, -1, -1}, /*  9 */
		{-1,  2, -1,  0}, /* 10 */
		{-1,  2, -1, -1}, /* 11 */
		{-1, -1, -1,  1}, /* 12 */
		{ 1, -1, -1, -1}, /* 13 */
		{-1, -1, -1,  0}, /* 14 */
		{-1, -1, -1, -1}, /* 15 */
	},
};

static _Thread_local char errbuf[256];

int msq_fail(int code, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(errbuf, sizeof errbuf, fmt, ap);
	va_end(ap);
	return code;
}

const char *msq_error(void)
{
	return errbuf;
}

void msq_clear(void)
{
	errbuf[0] = 0;
}
