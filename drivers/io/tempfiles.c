/* tempfiles.c: the table of live temporaries that SIGINT, SIGTERM, SIGHUP and exit() remove.
 *
 * The table is a list that only grows: an entry is published once with its path and never
 * changed or freed while the program runs, only its live flag is cleared. So a handler can walk
 * it at any moment, in any thread, without locks: it reads published pointers and flags (lock-
 * free atomics) and calls unlink(), all async-signal-safe. An entry costs its path's length; a
 * program opens one output per page at most, which it holds anyway.
 */
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "io/transport_int.h"

struct io_temp {
	io_temp_t *next;      /* set before publication, then fixed */
	pid_t owner;          /* the process that made it: a forked child leaves it alone */
	atomic_int live;
	char path[];
};

static _Atomic(io_temp_t *) head;
static pthread_once_t installed = PTHREAD_ONCE_INIT;
static const int caught[] = { SIGINT, SIGTERM, SIGHUP };
#define NCAUGHT (sizeof caught / sizeof caught[0])

static void remove_live(void)
{
	pid_t self = getpid();
	for (io_temp_t *e = atomic_load(&head); e; e = e->next)
		if (e->owner == self && atomic_load(&e->live))
			unlink(e->path);
}

static void on_signal(int sig)
{
	remove_live();
	/* SA_RESETHAND gave sig its default action back and SA_NODEFER left it unblocked, so this
	 * ends the program as the signal would have (status 128 + sig) */
	raise(sig);
}

/* A program that exits with an output still open failed: its temporaries go too. */
static void remove_at_exit(void)
{
	remove_live();
}

static void install(void)
{
	for (size_t k = 0; k < NCAUGHT; k++) {
		struct sigaction sa, old;
		if (sigaction(caught[k], NULL, &old) < 0)
			continue;
		/* leave ignored signals (nohup) and a program's own handlers alone */
		if ((old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL)
			continue;
		memset(&sa, 0, sizeof sa);
		sa.sa_handler = on_signal;
		sa.sa_flags = SA_RESETHAND | SA_NODEFER;
		sigemptyset(&sa.sa_mask);
		for (size_t j = 0; j < NCAUGHT; j++)
			if (j != k)
				sigaddset(&sa.sa_mask, caught[j]);
		sigaction(caught[k], &sa, NULL);
	}
	atexit(remove_at_exit);
}

io_temp_t *io_temp_add(const char *path)
{
	pthread_once(&installed, install);
	size_t n = strlen(path) + 1;
	io_temp_t *e = malloc(sizeof *e + n);
	if (!e)
		return NULL;
	memcpy(e->path, path, n);
	e->owner = getpid();
	atomic_init(&e->live, 1);
	e->next = atomic_load(&head);
	while (!atomic_compare_exchange_weak(&head, &e->next, e))
		;
	return e;
}

void io_temp_drop(io_temp_t *e)
{
	if (e)
		atomic_store(&e->live, 0);
}

void io_signals_block(sigset_t *old)
{
	sigset_t s;
	sigemptyset(&s);
	for (size_t k = 0; k < NCAUGHT; k++)
		sigaddset(&s, caught[k]);
	pthread_sigmask(SIG_BLOCK, &s, old);
}

void io_signals_restore(const sigset_t *old)
{
	pthread_sigmask(SIG_SETMASK, old, NULL);
}
