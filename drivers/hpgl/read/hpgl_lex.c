/* hpgl_lex.c: the HP-GL token layer shared by the reader and the job tracker (hpgl_lex.h). */
#include <stdlib.h>
#include <string.h>
#include "hpgl/read/hpgl_lex.h"

size_t hpgl_lex_number(const unsigned char *s, size_t n, size_t i, size_t *digits)
{
	size_t d = 0;
	if (s[i] == '-' || s[i] == '+')
		i++;
	while (i < n && hpgl_lex_digit(s[i]))
		i++, d++;
	if (i < n && s[i] == '.') {
		i++;
		while (i < n && hpgl_lex_digit(s[i]))
			i++, d++;
	}
	*digits = d;
	if (d && i < n && (s[i] == 'e' || s[i] == 'E') && i + 1 < n &&
			(hpgl_lex_digit(s[i + 1]) || s[i + 1] == '-' || s[i + 1] == '+')) {
		i++;
		if (s[i] == '-' || s[i] == '+')
			i++;
		while (i < n && hpgl_lex_digit(s[i]))
			i++;
	}
	return i;
}

double hpgl_lex_value(const unsigned char *p, size_t len)
{
	char buf[64];
	if (len > sizeof buf - 1)
		len = sizeof buf - 1;
	memcpy(buf, p, len);
	buf[len] = 0;
	return strtod(buf, NULL);
}
