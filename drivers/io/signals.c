/* signals.c: SIGINT, SIGTERM and SIGHUP during a device job: noted instead of ending the
 * program, so that the link's waits end and the job stops with its journal current and a line
 * that says where (transport.h, io_open_write). */
#include <errno.h>
#include <signal.h>
#include <string.h>
#include "io/link.h"

/* Signals during a device job (io_interrupted): the first one is noted, a second one ends the
 * program as the signal does. */
static volatile sig_atomic_t got_signal;
static const int caught[] = { SIGINT, SIGTERM, SIGHUP };
#define NCAUGHT (sizeof caught / sizeof caught[0])
static struct sigaction sig_old[NCAUGHT];
static int sig_ours[NCAUGHT], sig_links;

static void on_signal(int sig)
{
	if (got_signal) {
		signal(sig, SIG_DFL);
		raise(sig);
		return;
	}
	got_signal = sig;
}

/* A device link opens for writing: catch the signals the program leaves at their default. */
void tr_signals_take(void)
{
	if (sig_links++)
		return;
	got_signal = 0;
	for (size_t k = 0; k < NCAUGHT; k++) {
		struct sigaction sa, old;
		if (sigaction(caught[k], NULL, &old) < 0 || (old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL)
			continue;
		memset(&sa, 0, sizeof sa);
		sa.sa_handler = on_signal;   /* no SA_RESTART: a wait in a link ends with EINTR */
		sigemptyset(&sa.sa_mask);
		if (sigaction(caught[k], &sa, NULL) == 0) {
			sig_old[k] = old;
			sig_ours[k] = 1;
		}
	}
}

/* The last writing link closed: the signals as they were. */
void tr_signals_give(void)
{
	if (--sig_links)
		return;
	for (size_t k = 0; k < NCAUGHT; k++)
		if (sig_ours[k]) {
			sigaction(caught[k], &sig_old[k], NULL);
			sig_ours[k] = 0;
		}
}

int io_interrupted(void)
{
	return got_signal;
}

int tr_check_interrupt(io_transport_t *t)
{
	int sig = got_signal;
	if (!sig)
		return 0;
	io_link_tempfail(t, "interrupted by %s after %llu bytes", sig == SIGINT ? "SIGINT (Ctrl-C)"
		: sig == SIGTERM ? "SIGTERM" : "SIGHUP", t->link_out);
	t->io_errno = EINTR;
	return -1;
}
