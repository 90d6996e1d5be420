/* pdfobj.c: the PDF file's objects: numbered lists, object numbers and their offsets for the xref. */
#include <stdlib.h>
#include "ps/pdf_int.h"

int pdf_list_add(psd_t *p, pdf_list_t *l, uint64_t v)
{
	if (l->n == l->cap) {
		size_t n = l->cap ? l->cap * 2 : 16;
		uint64_t *q = realloc(l->v, n * sizeof *q);
		if (!q)
			return dev_fail(p->dev, META_ENOMEM, "out of memory");
		l->v = q;
		l->cap = n;
	}
	l->v[l->n++] = v;
	return 0;
}

unsigned pdf_new_obj(pdf_t *s)
{
	if (pdf_list_add(&s->p, &s->offsets, 0))
		return 0;
	return (unsigned)s->offsets.n;
}

void pdf_begin_obj(pdf_t *s, unsigned n)
{
	s->offsets.v[n - 1] = s->p.out.pos;
	dev_w_printf(&s->p.out, "%u 0 obj\n", n);
}

int pdf_failed(pdf_t *s)
{
	if (s->p.out.err)
		return psd_out_fail(&s->p);
	return 0;
}
