/* test_tr_links.c: the device links' shared parts: the query parser, journal= and flow=escb
 * refused while no print language is registered (io/ knows none), the journal's resumable
 * boundaries and state restore, and a dropped TCP connection reported as a temporary failure. */
#define _XOPEN_SOURCE 700   /* posix_openpt, ptsname */
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <unistd.h>
#include "hpgl/hpgl_link.h"
#include "io/journal.h"
#include "io/link.h"
#include "unit.h"

static void query(void)
{
	const char *q = "baud=9600&flow=escb";
	char k[16], v[16];
	CHECK(tr_query_next(&q, k, sizeof k, v, sizeof v) == 1 && !strcmp(k, "baud") && !strcmp(v, "9600"), "first pair");
	CHECK(tr_query_next(&q, k, sizeof k, v, sizeof v) == 1 && !strcmp(k, "flow") && !strcmp(v, "escb"), "second pair");
	CHECK(tr_query_next(&q, k, sizeof k, v, sizeof v) == 0, "end of the query");
	q = "novalue&a=1";
	CHECK(tr_query_next(&q, k, sizeof k, v, sizeof v) == -1, "a pair without '=' is refused");
	CHECK(tr_query_next(&q, k, sizeof k, v, sizeof v) == 1 && !strcmp(k, "a"), "and the next one still read");
	long x;
	CHECK(tr_parse_long("115200", 1, 4000000, &x) == 0 && x == 115200, "a number in range");
	CHECK(tr_parse_long("12x", 1, 100, &x) < 0 && tr_parse_long("0", 1, 100, &x) < 0, "junk and out of range refused");
}

/* io/ knows no print language: before one is registered, a journal and flow=escb are refused at
 * the open, in one line, before anything is created or sent (a journal file included). */
static void unregistered(void)
{
	char dir[] = "/tmp/locus-nl.XXXXXX", path[64], name[160], err[400];
	if (!mkdtemp(dir)) {
		CHECK(0, "mkdtemp");
		return;
	}
	snprintf(path, sizeof path, "%s/j", dir);
	CHECK(io_lang() == NULL, "no language before one is registered");
	CHECK(jn_create(path, "usb:1:2?journal=x", err, sizeof err) == NULL && strstr(err, "registers none")
		&& access(path, F_OK) != 0, "no language: jn_create refuses, and writes no file: %s", err);
	snprintf(name, sizeof name, "tcp:127.0.0.1:1?journal=%s", path);
	io_transport_t *t = io_open_write(name, err, sizeof err);
	CHECK(t == NULL && strstr(err, "registers none") && !strchr(err, '\n'), "no language: journal= refused at the open: %s", err);
	if (t)
		io_close(t, IO_ABORT);
	rmdir(dir);
	int m = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
	if (m >= 0 && grantpt(m) == 0 && unlockpt(m) == 0 && ptsname(m)) {
		snprintf(name, sizeof name, "serial:%s?flow=escb&timeout=2", ptsname(m));
		t = io_open_write(name, err, sizeof err);
		char got[16];
		ssize_t g = read(m, got, sizeof got);   /* (non-blocking: nothing was sent) */
		CHECK(t == NULL && strstr(err, "flow=escb needs the pacing") && g <= 0,
			"no language: flow=escb refused at the open, nothing sent: %s", err);
		if (t)
			io_close(t, IO_ABORT);
	} else
		CHECK(0, "a pseudo-terminal for the serial link");
	if (m >= 0)
		close(m);
	hpgl_link_register();
	CHECK(io_lang() == &hpgl_link_lang && !strcmp(io_lang()->name, "HP-GL"), "HP-GL registered");
}

static void journal(void)
{
	char dir[] = "/tmp/locus-jn.XXXXXX", path[64], err[300], where[700], line[256];
	if (!mkdtemp(dir)) {
		CHECK(0, "mkdtemp");
		return;
	}
	snprintf(path, sizeof path, "%s/j", dir);
	const char job[] = "IN;VS20;SP2;PA100,200;PD300,400,500,600;PU;LT2;PR10,0;";
	jn_t *j = jn_create(path, "usb:03f0:0107?journal=J", err, sizeof err);
	CHECK(j != NULL, "journal created: %s", j ? "" : err);
	if (!j)
		return;
	/* the device took up to the middle of 500: the last whole pair is 300,400 */
	size_t cut = (size_t)(strstr(job, "500") - job) + 1;
	CHECK(jn_ack(j, job, cut) == 0, "acknowledged %zu bytes", cut);
	jn_where(j, where, sizeof where);
	size_t safe = (size_t)(strstr(job, "500") - job);
	char want[200];
	snprintf(want, sizeof want, "(byte %zu of the job) reached; resume with -o 'usb:03f0:0107?resume=J'", safe);
	CHECK(strstr(where, want) != NULL, "where: %s", where);
	jn_close(j, 0);
	FILE *f = fopen(path, "r");
	int restore_ok = 0, state_ok = 0;
	while (f && fgets(line, sizeof line, f)) {
		restore_ok |= !strcmp(line, "restore SP2;VS20;PU;PA300,400;PD;PD\n");
		state_ok |= !strcmp(line, "state interrupted\n");
	}
	if (f)
		fclose(f);
	CHECK(restore_ok && state_ok, "the journal restores pen, velocity, position, pen down, and PD goes on");
	/* resume: the same job is skipped to the boundary, then the rest goes with the restore first */
	j = jn_resume(path, "usb:03f0:0107?resume=J", err, sizeof err);
	CHECK(j != NULL, "resume opened: %s", j ? "" : err);
	if (j) {
		const char *restore = NULL;
		long k = jn_skip(j, job, sizeof job - 1, &restore, err, sizeof err);
		/* the device held "5" of 500: the closer finishes that command with the job's own bytes */
		CHECK(k == (long)safe && restore && !strcmp(restore, "00,600;;SP2;VS20;PU;PA300,400;PD;PD"),
			"skipped %ld bytes, then the closer of the held command and the restore: %s", k, restore ? restore : "");
		CHECK(jn_ack(j, job + safe, sizeof job - 1 - safe) == 0 && jn_close(j, 1) == 0, "the rest acknowledged, done");
	}
	j = jn_resume(path, "x", err, sizeof err);
	CHECK(!j && strstr(err, "nothing to resume"), "a finished job is not resumed: %s", err);
	/* another job: refused at the boundary */
	j = jn_create(path, "x", err, sizeof err);
	if (j) {
		jn_ack(j, job, cut);
		jn_close(j, 0);
	}
	j = jn_resume(path, "x", err, sizeof err);
	const char *restore = NULL;
	const char other[] = "IN;VS20;SP3;PA100,200;PD300,400,500,600;";
	CHECK(j && jn_skip(j, other, sizeof other - 1, &restore, err, sizeof err) < 0 && strstr(err, "differs"),
		"another job is refused: %s", err);
	jn_close(j, 0);
	unlink(path);
	rmdir(dir);
}

static void dropped(void)
{
	int ls = socket(AF_INET, SOCK_STREAM, 0);
	struct sockaddr_in sa = { .sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
	socklen_t sl = sizeof sa;
	if (ls < 0 || bind(ls, (struct sockaddr *)&sa, sizeof sa) || listen(ls, 1) || getsockname(ls, (struct sockaddr *)&sa, &sl)) {
		CHECK(0, "loopback listener");
		return;
	}
	char name[64], err[600];
	snprintf(name, sizeof name, "tcp:127.0.0.1:%d?timeout=2", ntohs(sa.sin_port));
	io_transport_t *t = io_open_write(name, err, sizeof err);
	CHECK(t != NULL, "connected: %s", t ? "" : err);
	if (!t)
		return;
	int c = accept(ls, NULL, NULL);
	struct linger lg = { 1, 0 };
	setsockopt(c, SOL_SOCKET, SO_LINGER, &lg, sizeof lg);
	close(c);   /* a reset: the printer dropped us */
	CHECK(!io_temporary(t), "no failure yet, nothing temporary");
	static char buf[1 << 16];
	int rc = 0;
	for (int k = 0; k < 64 && rc == 0; k++)
		rc = io_write(t, buf, sizeof buf) || io_flush(t);
	CHECK(rc != 0 && io_temporary(t) && strstr(io_error(t), "dropped the connection"),
		"a dropped connection fails as temporary: %s", io_error(t));
	io_close(t, IO_ABORT);
	close(ls);
}

int main(void)
{
	query();
	unregistered();   /* then HP-GL registered: journal= keeps its checkpoints */
	journal();
	dropped();
	return UNIT_DONE();
}
