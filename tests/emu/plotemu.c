/* plotemu.c: an HP 7475A-like pen plotter behind a pseudo-terminal (or a TCP port) that models
 * its line: bytes arrive at the byte rate of the baud setting the sender chose, a 1024-byte
 * buffer drops silently what overflows it, the pen drains it at a modelled speed, XON/XOFF or
 * CTS stop the sender (with bytes still in flight), and ESC.B/ESC.L/ESC.O/ESC.E and
 * OI/OS/OE/OA are answered. It runs one command (@TTY@ or @PORT@ in its arguments replaced),
 * then reports what arrived and compares it with the HP-GL the job should have delivered.
 *
 *   emu-plotter [options] -- CMD ARGS...
 *   --handshake xonxoff|hardware|none  the plotter's own setting (default xonxoff)
 *   --buffer N      input buffer in bytes (1024)     --speed PU/S  top pen speed (VS up to it)
 *   --in-flight N   bytes the sender's UART still sends after XOFF/CTS (16)
 *   --pen-change S  seconds per pen change (0.5)    --mute  answer no query (one-way cable)
 *   --pen-scale F   the pen works F times faster than a real one (the line does not)
 *   --deadline S    kill the command after S seconds (60)
 *   --tcp           listen on 127.0.0.1 instead; --drop-after N: drop the first connection
 *                   after N bytes (what its TCP already acknowledged is still taken: the
 *                   printer has it; the rest is refused with a reset); --rate B/S: the
 *                   network's byte rate; --rcvbuf N: the socket's receive buffer (4096; 0: the
 *                   system's); --reset-after N: after reading N bytes of the first
 *                   connection, close it at once with a reset (SO_LINGER 0), as a printer
 *                   switched off does: what waited unread in its receive buffer is lost
 *   --hangup-after N  the line goes away (the pseudo-terminal closes) after N accepted bytes
 *   --record FILE   the HP-GL received (escapes and output instructions left out)
 *   --expect FILE   compare with this HP-GL: bytes, and strokes through the HP-GL reader
 * Prints one line "child=S received=N accepted=N dropped=N ... strokes=same|differ ...";
 * exits 0 when the child exited 0 and nothing differed, else 1. */
#define _GNU_SOURCE   /* posix_openpt, ptsname, accept4 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include "emu.h"

typedef struct {
	/* settings */
	int handshake;            /* 'x', 'h', 'n' */
	size_t bufsize, in_flight;
	double speed, top;        /* pen speed, and the top speed VS cannot exceed (units/s) */
	double rate;              /* line bytes per second (0: from the slave's termios) */
	int honours;              /* the sender stops when asked (its termios, or TCP) */
	/* the buffer (a ring) */
	unsigned char *ring;
	size_t head, count, peak;
	/* the record of accepted bytes, and output-instruction ranges to leave out */
	unsigned char *rec;
	size_t nrec, caprec;
	size_t cut[256][2];
	size_t ncut;
	/* counters */
	long long received, dropped, escapes, xoffs;
	int stopped;              /* XOFF sent / CTS low */
	double stopped_at;
	long long stop_budget;    /* bytes still accepted after the stop */
	/* the escape parser */
	int esc;                  /* 0, 1 after ESC, 2 after ESC., 3 skipping to ':' */
	/* the pen */
	double busy_until, x, y;
	int pen, pendown, relative;
	char cmd[3];
	int ncmd;
	size_t cmd_start;         /* record offset of the command being read */
	char num[32];
	int nnum;
	double args[2];
	int nargs;
	int in_label;
	int out_fd;               /* where replies go */
	int mute;                 /* answers nothing (a one-way cable) */
	double pen_change;        /* seconds per SP */
	double scale;             /* the pen works this many times faster than a real one */
} emu_t;

static double now_s(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static void reply(emu_t *e, const char *s)
{
	size_t n = strlen(s);
	if (e->mute && s[0] != 0x11 && s[0] != 0x13)
		return;
	while (n > 0) {
		ssize_t w = write(e->out_fd, s, n);
		if (w <= 0)
			return;
		s += w;
		n -= (size_t)w;
	}
}

static void replyf(emu_t *e, const char *fmt, long a, long b, long c, int three)
{
	char buf[64];
	if (three)
		snprintf(buf, sizeof buf, fmt, a, b, c);
	else
		snprintf(buf, sizeof buf, fmt, a);
	reply(e, buf);
}

static void record(emu_t *e, unsigned char c)
{
	if (e->nrec == e->caprec) {
		e->caprec = e->caprec ? 2 * e->caprec : 65536;
		e->rec = realloc(e->rec, e->caprec);
		if (!e->rec)
			exit(70);
	}
	e->rec[e->nrec++] = c;
}

/* A byte arrived on the line. */
static void arrive(emu_t *e, unsigned char c)
{
	e->received++;
	if (e->esc == 0 && c == 27) {
		e->esc = 1;
		return;
	}
	if (e->esc == 1) {
		e->esc = c == '.' ? 2 : 0;
		return;
	}
	if (e->esc == 2) {
		e->escapes++;
		e->esc = 0;
		switch (c) {
		case 'B': replyf(e, "%ld\r", (long)(e->bufsize - e->count), 0, 0, 0); break;
		case 'L': replyf(e, "%ld\r", (long)e->bufsize, 0, 0, 0); break;
		case 'O': replyf(e, "%ld\r", e->count == 0 ? 8L : 0L, 0, 0, 0); break;
		case 'E': replyf(e, "%ld\r", e->dropped ? 16L : 0L, 0, 0, 0); break;
		case 'A': reply(e, "7475A,0\r"); break;
		case 'R': break;
		default: e->esc = 3;   /* ESC.H ESC.I ESC.M ESC.N ESC.@ ...: parameters up to ':' */
		}
		return;
	}
	if (e->esc == 3) {
		if (c == ':')
			e->esc = 0;
		return;
	}
	if (e->count == e->bufsize) {
		e->dropped++;   /* a full 7475A says nothing */
		return;
	}
	e->ring[(e->head + e->count) % e->bufsize] = c;
	e->count++;
	if (e->count > e->peak)
		e->peak = e->count;
	record(e, c);
}

/* The pen finished reading a number or a command: move and take the time it takes. */
static void take_pair(emu_t *e)
{
	double nx = e->relative ? e->x + e->args[0] : e->args[0];
	double ny = e->relative ? e->y + e->args[1] : e->args[1];
	e->busy_until += hypot(nx - e->x, ny - e->y) / e->speed / e->scale;
	e->x = nx;
	e->y = ny;
}

static void end_number(emu_t *e)
{
	if (!e->nnum)
		return;
	e->num[e->nnum] = 0;
	double v = atof(e->num);
	e->nnum = 0;
	if (!strcmp(e->cmd, "VS")) {
		if (v > 0)
			e->speed = v * 400.0 < e->top ? v * 400.0 : e->top;   /* cm/s, up to the top speed */
		return;
	}
	if (!strcmp(e->cmd, "SP")) {
		e->pen = (int)v;
		e->busy_until += e->pen_change / e->scale;   /* the carousel turns */
		return;
	}
	if (strcmp(e->cmd, "PU") && strcmp(e->cmd, "PD") && strcmp(e->cmd, "PA") && strcmp(e->cmd, "PR"))
		return;
	e->args[e->nargs++] = v;
	if (e->nargs == 2) {
		take_pair(e);
		e->nargs = 0;
	}
}

static void end_command(emu_t *e, size_t end)
{
	end_number(e);
	if (e->ncmd == 2 && e->cmd[0] == 'O' && strchr("ISEA", e->cmd[1])) {
		switch (e->cmd[1]) {
		case 'I': reply(e, "7475A\r"); break;
		case 'S': replyf(e, "%ld\r", 8L | 16L | (long)e->pendown, 0, 0, 0); break;
		case 'E': reply(e, "0\r"); break;
		case 'A': replyf(e, "%ld,%ld,%ld\r", lround(e->x), lround(e->y), e->pen, 1); break;
		}
		if (e->ncut < sizeof e->cut / sizeof e->cut[0]) {
			e->cut[e->ncut][0] = e->cmd_start;
			e->cut[e->ncut][1] = end;
			e->ncut++;
		}
	}
	e->ncmd = 0;
	e->nargs = 0;
}

/* The pen takes one byte from the buffer (when it is not busy moving). */
static void consume(emu_t *e)
{
	unsigned char c = e->ring[e->head];
	size_t at = e->nrec - e->count;   /* its offset in the record */
	e->head = (e->head + 1) % e->bufsize;
	e->count--;
	if (e->in_label) {
		if (c == 3)
			e->in_label = 0;
		e->busy_until += 0.05 / e->scale;   /* a character's strokes, at the pen's pace */
		return;
	}
	if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z')) {
		if (e->ncmd == 2)
			end_command(e, at);
		if (e->ncmd == 0)
			e->cmd_start = at;
		e->cmd[e->ncmd++] = (char)(c & ~0x20);
		e->cmd[e->ncmd] = 0;
		if (e->ncmd == 2) {
			if (!strcmp(e->cmd, "PU"))
				e->pendown = 0;
			else if (!strcmp(e->cmd, "PD"))
				e->pendown = 1;
			else if (!strcmp(e->cmd, "PA"))
				e->relative = 0;
			else if (!strcmp(e->cmd, "PR"))
				e->relative = 1;
			else if (!strcmp(e->cmd, "LB"))
				e->in_label = 1;
			else if (!strcmp(e->cmd, "IN"))
				e->relative = 0;
		}
		return;
	}
	if ((c >= '0' && c <= '9') || c == '-' || c == '.' || c == '+') {
		if (e->nnum + 1 < (int)sizeof e->num)
			e->num[e->nnum++] = (char)c;
		return;
	}
	if (c == ';')
		end_command(e, at + 1);
	else
		end_number(e);
}

/* Let the pen work until now. */
static void plot(emu_t *e, double now)
{
	if (e->busy_until < now - 0.01)
		e->busy_until = now - 0.01;   /* an idle pen saves no time */
	while (e->count > 0 && e->busy_until <= now)
		consume(e);
}

/* Ask the sender to stop or go on, as the plotter's handshake does. */
static void handshake(emu_t *e)
{
	size_t fr = e->bufsize - e->count;
	if (e->handshake == 'n')
		return;
	if (!e->stopped && fr < e->bufsize / 8) {
		e->stopped = 1;
		e->stopped_at = now_s();
		e->xoffs++;
		e->stop_budget = (long long)e->in_flight;
		if (e->handshake == 'x')
			reply(e, "\x13");
	} else if (e->stopped && fr >= e->bufsize / 2) {
		e->stopped = 0;
		if (e->handshake == 'x')
			reply(e, "\x11");
	}
}

static int bits_per_char(const struct termios *t)
{
	int b = (t->c_cflag & CSIZE) == CS5 ? 5 : (t->c_cflag & CSIZE) == CS6 ? 6 : (t->c_cflag & CSIZE) == CS7 ? 7 : 8;
	return 1 + b + (t->c_cflag & PARENB ? 1 : 0) + (t->c_cflag & CSTOPB ? 2 : 1);
}

static long baud_of(speed_t s)
{
	static const struct { speed_t c; long b; } t[] = {
		{ B300, 300 }, { B600, 600 }, { B1200, 1200 }, { B2400, 2400 }, { B4800, 4800 },
		{ B9600, 9600 }, { B19200, 19200 }, { B38400, 38400 }, { B57600, 57600 },
		{ B115200, 115200 }, { B230400, 230400 }, { B460800, 460800 }, { B921600, 921600 },
	};
	for (size_t k = 0; k < sizeof t / sizeof t[0]; k++)
		if (t[k].c == s)
			return t[k].b;
	return 0;
}

/* argv with @TTY@ / @PORT@ replaced. */
static char **subst(char **argv, const char *key, const char *val)
{
	int n = 0;
	while (argv[n])
		n++;
	char **v = calloc((size_t)n + 1, sizeof *v);
	for (int i = 0; v && i < n; i++) {
		const char *p = strstr(argv[i], key);
		if (!p) {
			v[i] = argv[i];
			continue;
		}
		size_t l = strlen(argv[i]) + strlen(val) + 1;
		v[i] = malloc(l);
		if (!v[i])
			exit(70);
		snprintf(v[i], l, "%.*s%s%s", (int)(p - argv[i]), argv[i], val, p + strlen(key));
	}
	return v;
}

static void reset_line(emu_t *e)
{
	e->head = e->count = 0;
	e->nrec = 0;
	e->ncut = 0;
	e->esc = e->ncmd = e->nnum = e->nargs = e->in_label = 0;
	e->stopped = 0;
	e->relative = 0;
}

int main(int argc, char **argv)
{
	emu_t e;
	memset(&e, 0, sizeof e);
	e.handshake = 'x';
	e.bufsize = 1024;
	e.in_flight = 16;
	e.pen_change = 0.5;
	e.scale = 1;
	e.speed = e.top = 15240;   /* 38.1 cm/s, the 7475A's top speed */
	const char *rec_path = NULL, *expect = NULL;
	int tcp = 0;
	long long drop_after = -1, hangup_after = -1, reset_after = -1;
	int rcvbuf = 4096;
	double deadline = 60;
	int i;
	for (i = 1; i < argc && strcmp(argv[i], "--"); i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
		if (!strcmp(a, "--handshake")) e.handshake = v[0] == 'h' ? 'h' : v[0] == 'n' ? 'n' : 'x', i++;
		else if (!strcmp(a, "--buffer")) e.bufsize = (size_t)atol(v), i++;
		else if (!strcmp(a, "--speed")) e.speed = e.top = atof(v), i++;
		else if (!strcmp(a, "--in-flight")) e.in_flight = (size_t)atol(v), i++;
		else if (!strcmp(a, "--rate")) e.rate = atof(v), i++;
		else if (!strcmp(a, "--record")) rec_path = v, i++;
		else if (!strcmp(a, "--expect")) expect = v, i++;
		else if (!strcmp(a, "--drop-after")) drop_after = atoll(v), i++;
		else if (!strcmp(a, "--reset-after")) reset_after = atoll(v), i++;
		else if (!strcmp(a, "--hangup-after")) hangup_after = atoll(v), i++;
		else if (!strcmp(a, "--pen-change")) e.pen_change = atof(v), i++;
		else if (!strcmp(a, "--mute")) e.mute = 1;
		else if (!strcmp(a, "--pen-scale")) e.scale = atof(v), i++;
		else if (!strcmp(a, "--deadline")) deadline = atof(v), i++;
		else if (!strcmp(a, "--tcp")) tcp = 1;
		else if (!strcmp(a, "--rcvbuf")) rcvbuf = atoi(v), i++;
		else {
			fprintf(stderr, "emu-plotter: unknown option %s\n", a);
			return 64;
		}
	}
	if (i + 1 >= argc || e.bufsize < 16 || e.speed <= 0 || e.scale <= 0) {
		fprintf(stderr, "usage: emu-plotter [options] -- CMD ARGS... (see tests/emu/plotemu.c)\n");
		return 64;
	}
	e.ring = malloc(e.bufsize);
	signal(SIGPIPE, SIG_IGN);
	char name[64];
	int master = -1, slave = -1, lsock = -1, conn = -1;
	if (tcp) {
		struct sockaddr_in sa = { .sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
		socklen_t sl = sizeof sa;
		lsock = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
		if (lsock >= 0 && rcvbuf > 0)   /* a printer's small network buffer (accepted sockets inherit it) */
			setsockopt(lsock, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
		if (lsock < 0 || bind(lsock, (struct sockaddr *)&sa, sizeof sa) || listen(lsock, 4)
			|| getsockname(lsock, (struct sockaddr *)&sa, &sl)) {
			perror("emu-plotter: listen");
			return 70;
		}
		snprintf(name, sizeof name, "%d", ntohs(sa.sin_port));
		e.honours = 1;
		if (e.rate <= 0)
			e.rate = 20000;
	} else {
		master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
		if (master < 0 || grantpt(master) || unlockpt(master) || !ptsname(master)) {
			perror("emu-plotter: pty");
			return 70;
		}
		snprintf(name, sizeof name, "%s", ptsname(master));
		slave = open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);   /* kept: its termios is the line */
		fcntl(master, F_SETFL, O_NONBLOCK);
	}
	char **cv = subst(argv + i + 1, tcp ? "@PORT@" : "@TTY@", name);
	pid_t pid = fork();
	if (pid == 0) {
		execvp(cv[0], cv);
		perror(cv[0]);
		_exit(127);
	}
	int status = -1, exited = 0;
	double started = now_s();
	double credit = 0, last = now_s(), first_at = 0, last_at = 0;
	long baud = 0;
	int bpc = 10, connections = 0;
	long long conn_bytes = 0, first_bytes = -1;   /* first: what the dropped connection took */
	for (;;) {
		if (!exited && waitpid(pid, &status, WNOHANG) == pid)
			exited = 1;
		int fd = master;
		if (tcp) {
			if (conn < 0) {
				struct pollfd pf = { lsock, POLLIN, 0 };
				if (poll(&pf, 1, exited ? 0 : 5) > 0) {
					conn = accept4(lsock, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
					connections++;
					conn_bytes = 0;
					reset_line(&e);
				} else if (exited)
					break;
				continue;
			}
			fd = conn;
		} else if (e.received == 0) {   /* the line as the sender set it up */
			struct termios tio;
			tcgetattr(slave, &tio);
			baud = baud_of(cfgetospeed(&tio));
			bpc = bits_per_char(&tio);
			e.honours = e.handshake == 'x' ? (tio.c_iflag & IXON) != 0
				: e.handshake == 'h' ? (tio.c_cflag & CRTSCTS) != 0 : 0;
		}
		e.out_fd = fd;
		double now = now_s();
		double rate = e.rate > 0 ? e.rate : (double)baud / bpc;
		credit += (now - last) * rate;
		last = now;
		plot(&e, now);
		handshake(&e);
		/* How many bytes the line lets arrive now, and whether the sender holds them back. */
		long long want = (long long)credit;
		if (e.stopped && e.honours) {
			if (want > e.stop_budget)
				want = e.stop_budget;
		} else if (e.honours && e.handshake != 'n') {
			/* a burst (the emulator was not scheduled for a while) still meets the stop where
			 * the buffer reaches it, as bytes arriving one by one would: up to the threshold
			 * and the bytes in flight after it */
			long long room = (long long)(e.bufsize - e.count) - (long long)(e.bufsize / 8) + 1
				+ (long long)e.in_flight;
			if (want > room)
				want = room > 0 ? room : 0;
		}
		if (tcp && want > (long long)(e.bufsize - e.count))
			want = (long long)(e.bufsize - e.count);   /* TCP holds what the buffer cannot */
		ssize_t r = 0;
		if (want > 0) {
			unsigned char tmp[4096];
			if (want > (long long)sizeof tmp)
				want = sizeof tmp;
			r = read(fd, tmp, (size_t)want);
			if (r > 0) {
				if (!first_at)
					first_at = now;
				last_at = now;
				for (ssize_t k = 0; k < r; k++)
					arrive(&e, tmp[k]);
				credit -= (double)r;
				conn_bytes += r;
				if (e.stopped && e.honours)
					e.stop_budget -= r;
				if (!tcp && hangup_after >= 0 && (long long)e.nrec >= hangup_after) {
					close(master);   /* the cable is pulled: the sender's writes fail */
					close(slave);
					waitpid(pid, &status, 0);
					exited = 1;
					break;
				}
				if (tcp && reset_after >= 0 && connections == 1 && conn_bytes >= reset_after) {
					/* switched off: the unread bytes in the socket are gone, the peer gets a reset */
					struct linger lg = { 1, 0 };
					setsockopt(conn, SOL_SOCKET, SO_LINGER, &lg, sizeof lg);
					close(conn);
					conn = -1;
					first_bytes = conn_bytes;
					continue;
				}
				if (tcp && drop_after >= 0 && connections == 1 && conn_bytes >= drop_after) {
					/* The printer drops the first job once. Shut down first: from then on its TCP
					 * refuses new data with a reset instead of acknowledging it; what it had
					 * acknowledged already is in its buffer, and it plots that. */
					shutdown(conn, SHUT_RDWR);
					for (;;) {
						ssize_t g = read(conn, tmp, sizeof tmp);
						if (g <= 0)
							break;
						for (ssize_t k = 0; k < g; k++) {
							if (e.count == e.bufsize)
								consume(&e);   /* the pen makes room */
							arrive(&e, tmp[k]);
						}
						conn_bytes += g;
					}
					close(conn);
					conn = -1;
					first_bytes = conn_bytes;
					continue;
				}
			} else if (tcp && r == 0) {
				/* the job ended: the pen finishes, then the printer closes */
				while (e.count > 0)
					consume(&e);
				close(conn);
				conn = -1;
				continue;
			}
		}
		if (r <= 0 || credit < 1) {
			if (credit > 2)
				credit = 2;   /* an idle line stores no time */
		}
		if (!tcp && exited && e.stopped && e.honours && now - e.stopped_at > 2)
			break;   /* the sender is gone and its port stayed held: what it held is lost */
		if (!exited && now - started > deadline) {
			kill(pid, SIGKILL);   /* a test never hangs */
			fprintf(stderr, "emu-plotter: the command ran past %.0f s: killed\n", deadline);
		}
		if (!tcp && exited && r <= 0 && want > 0) {
			struct pollfd pf = { master, POLLIN, 0 };
			if (poll(&pf, 1, 0) <= 0 || (pf.revents & POLLHUP))
				break;
		}
		struct pollfd pf = { fd, POLLIN, 0 };
		poll(&pf, 1, 1);
		if (!(pf.revents & POLLIN))
			continue;
		struct timespec ts = { 0, 200000 };
		nanosleep(&ts, NULL);
	}
	while (e.count > 0)
		consume(&e);
	end_command(&e, e.nrec);
	/* the record without the output instructions the link sent */
	unsigned char *job = malloc(e.nrec + 1);
	size_t nj = 0, c = 0;
	for (size_t k = 0; k < e.nrec; k++) {
		while (c < e.ncut && k >= e.cut[c][1])
			c++;
		if (c < e.ncut && k >= e.cut[c][0] && k < e.cut[c][1])
			continue;
		job[nj++] = e.rec[k];
	}
	if (rec_path) {
		FILE *f = fopen(rec_path, "wb");
		if (f) {
			fwrite(job, 1, nj, f);
			fclose(f);
		}
	}
	double secs = last_at - first_at;
	int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
	printf("child=%d received=%lld accepted=%zu dropped=%lld peak=%zu xoff=%lld escapes=%lld "
		"queries=%zu baud=%ld bits=%d seconds=%.3f rate=%.0f line=%.0f connections=%d first=%lld", code,
		e.received, e.nrec, e.dropped, e.peak, e.xoffs, e.escapes, e.ncut, baud, bpc, secs,
		secs > 0 ? (double)e.received / secs : 0, e.rate > 0 ? e.rate : (double)baud / bpc, connections,
		first_bytes);
	int bad = code != 0;
	if (expect)
		bad |= emu_compare(job, nj, expect);
	printf("\n");
	free(job);
	free(e.rec);
	free(e.ring);
	for (int k = 0; cv[k]; k++)
		if (cv[k] != argv[i + 1 + k])
			free(cv[k]);
	free(cv);
	return bad ? 1 : 0;
}
