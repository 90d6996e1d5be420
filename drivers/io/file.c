/* file.c: the file transport: regular files through a temporary renamed into place, devices,
 * pipes, sockets and terminals written in place. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>
#include "io/transport_int.h"

/* Candidate temporaries: TARGET.PID-K.tmp for K = 0, 1, 2 ... counted over the process; a name
 * that exists (whatever it is, a symlink included) is skipped, up to this many per output. */
#define IO_TMP_TRIES 64

static atomic_uint next_candidate;
static mode_t new_mode;          /* 0666 & ~umask */
static pthread_once_t umask_once = PTHREAD_ONCE_INIT;

static void read_umask(void)
{
	mode_t m = umask(022);
	umask(m);
	new_mode = 0666 & ~m;
}

enum { KIND_NEW, KIND_REGULAR, KIND_IN_PLACE, KIND_DIR };

typedef struct {
	int kind;
	char *path;        /* NEW, REGULAR: the file to replace (malloc'd) */
	mode_t mode;       /* the mode the replacement gets */
	uid_t uid;         /* REGULAR: its owner and group, kept where the system allows */
	gid_t gid;
} target_t;

static int fail(char *err, size_t errlen, const char *name, const char *what)
{
	snprintf(err, errlen, "%s: %s: %s", name, what, strerror(errno));
	return -1;
}

/* /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N: the descriptor, else -1. Written
 * through a copy of the descriptor, so that a shell's `>>` or a shared offset still holds. */
static int fd_name(const char *name)
{
	const char *p = NULL;
	if (!strcmp(name, "/dev/stdout"))
		return 1;
	if (!strcmp(name, "/dev/stderr"))
		return 2;
	if (!strncmp(name, "/dev/fd/", 8))
		p = name + 8;
	else if (!strncmp(name, "/proc/self/fd/", 14))
		p = name + 14;
	if (!p || *p < '0' || *p > '9' || strlen(p) > 9)
		return -1;
	char *e;
	long v = strtol(p, &e, 10);
	return *e ? -1 : (int)v;
}

/* What name is: a regular file (through any symlinks: the link stays, its file is replaced),
 * nothing yet (a dangling symlink is replaced), a directory, or something written in place. */
static int classify(const char *name, target_t *tg)
{
	struct stat st;
	pthread_once(&umask_once, read_umask);
	memset(tg, 0, sizeof *tg);
	tg->mode = new_mode;
	tg->kind = KIND_NEW;
	if (lstat(name, &st) < 0) {
		if (errno != ENOENT)
			return -1;
	} else if (S_ISLNK(st.st_mode) && stat(name, &st) < 0) {
		if (errno != ENOENT)
			return -1;
	} else if (S_ISDIR(st.st_mode)) {
		tg->kind = KIND_DIR;
	} else if (!S_ISREG(st.st_mode)) {
		tg->kind = KIND_IN_PLACE;
	} else {
		tg->kind = KIND_REGULAR;
		tg->mode = st.st_mode & 0777;
		tg->uid = st.st_uid;
		tg->gid = st.st_gid;
	}
	if (tg->kind == KIND_NEW || tg->kind == KIND_REGULAR) {
		char *real = tg->kind == KIND_REGULAR ? realpath(name, NULL) : NULL;
		tg->path = real ? real : strdup(name);
		if (!tg->path)
			return -1;
	}
	return 0;
}

static int connect_unix(const char *name)
{
	struct sockaddr_un sa;
	if (strlen(name) >= sizeof sa.sun_path) {
		errno = ENAMETOOLONG;
		return -1;
	}
	memset(&sa, 0, sizeof sa);
	sa.sun_family = AF_UNIX;
	strcpy(sa.sun_path, name);
	int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (fd >= 0 && connect(fd, (struct sockaddr *)&sa, sizeof sa) < 0) {
		int e = errno;
		close(fd);
		errno = e;
		fd = -1;
	}
	return fd;
}

/* A device, FIFO, socket or terminal: opened as it is, never created, truncated or renamed.
 * 1 when name turned into a regular file meanwhile (the caller starts again). */
static int open_in_place(io_transport_t *t, char *err, size_t errlen)
{
	struct stat st;
	int sock = stat(t->name, &st) == 0 && S_ISSOCK(st.st_mode);
	int fd = sock ? connect_unix(t->name) : open(t->name, O_WRONLY | O_NOCTTY | O_CLOEXEC);
	if (fd < 0)
		return fail(err, errlen, t->name, "cannot open");
	if (!sock && fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
		close(fd);
		return 1;
	}
	t->fd = fd;
	t->in_place = 1;
	return 0;
}

/* A new temporary beside tg->path, made with O_EXCL and O_NOFOLLOW: an existing name, a symlink
 * above all, is never opened. Registered for removal by a signal before anything is written. */
static int open_temp(io_transport_t *t, target_t *tg, char *err, size_t errlen)
{
	if (tg->kind == KIND_REGULAR && access(tg->path, W_OK) < 0)
		return fail(err, errlen, t->name, "cannot write");
	size_t n = strlen(tg->path) + 32;
	char *tmp = malloc(n);
	if (!tmp) {
		io_oom(err, errlen, t->name);
		return -1;
	}
	int fd = -1, e = 0;
	for (int k = 0; k < IO_TMP_TRIES && fd < 0; k++) {
		sigset_t old;
		snprintf(tmp, n, "%s.%ld-%u.tmp", tg->path, (long)getpid(), atomic_fetch_add(&next_candidate, 1));
		io_signals_block(&old);
		fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC, 0600);
		e = errno;
		if (fd >= 0 && !(t->live = io_temp_add(tmp))) {
			close(fd);
			unlink(tmp);
			fd = -1;
			e = ENOMEM;
		}
		io_signals_restore(&old);
		if (fd < 0 && e != EEXIST)
			break;
	}
	if (fd < 0) {
		free(tmp);
		errno = e;
		return fail(err, errlen, t->name, "cannot create a temporary file beside it");
	}
	t->fd = fd;
	t->tmp = tmp;
	t->target = tg->path;
	tg->path = NULL;
	/* the owner and group of a replaced file too, where allowed (root; a group of one's own);
	 * before the mode, as a change of owner may clear mode bits */
	if (tg->kind == KIND_REGULAR && fchown(fd, tg->uid, tg->gid) < 0 && fchown(fd, (uid_t)-1, tg->gid) < 0) {
		/* neither allowed: the file becomes this user's, as a new file would */
	}
	if (fchmod(fd, tg->mode) < 0) {
		e = errno;
		io_file_discard(t);
		errno = e;
		return fail(err, errlen, t->name, "cannot set the mode of its temporary file");
	}
	return 0;
}

int io_file_open(io_transport_t *t, char *err, size_t errlen)
{
	if (!t->name[0]) {
		snprintf(err, errlen, "the output name is empty");
		return -1;
	}
	int n = fd_name(t->name);
	if (n >= 0) {
		t->fd = fcntl(n, F_DUPFD_CLOEXEC, 3);
		if (t->fd < 0)
			return fail(err, errlen, t->name, "cannot write");
		t->in_place = 1;
		return 0;
	}
	for (int again = 0; again < 3; again++) {
		target_t tg;
		int rc;
		if (classify(t->name, &tg) < 0)
			return fail(err, errlen, t->name, "cannot write");
		switch (tg.kind) {
		case KIND_DIR:
			errno = EISDIR;
			return fail(err, errlen, t->name, "cannot write");
		case KIND_IN_PLACE:
			if ((rc = open_in_place(t, err, errlen)) != 1)
				return rc;
			break;
		default:
			rc = open_temp(t, &tg, err, errlen);
			free(tg.path);
			return rc;
		}
	}
	errno = EAGAIN;
	return fail(err, errlen, t->name, "cannot write");
}

int io_file_commit(io_transport_t *t, const char *target)
{
	int rc = 0;
	target_t tg = { KIND_REGULAR, NULL, 0, 0, 0 };
	const char *dest = t->target, *shown = t->name;
	if (target && strcmp(target, t->name)) {
		/* a name chosen after the fact (page k of a job): the same rules as at open */
		shown = target;
		if (classify(target, &tg) < 0) {
			rc = -1;
		} else if (tg.kind == KIND_DIR || tg.kind == KIND_IN_PLACE) {
			errno = tg.kind == KIND_DIR ? EISDIR : EEXIST;
			rc = -1;
		} else {
			if (tg.kind == KIND_REGULAR && chown(t->tmp, tg.uid, tg.gid) < 0 && chown(t->tmp, (uid_t)-1, tg.gid) < 0) {
				/* as at open: the owner stays this user where it may not be kept */
			}
			rc = chmod(t->tmp, tg.mode);
		}
		dest = tg.path;
	}
	if (rc == 0) {
		sigset_t old;
		io_signals_block(&old);
		rc = rename(t->tmp, dest);
		if (rc == 0) {
			io_temp_drop(t->live);
			free(t->tmp);
			t->tmp = NULL;
		}
		io_signals_restore(&old);
	}
	if (rc < 0) {
		t->io_errno = errno;
		snprintf(t->err, sizeof t->err, "%s: %s: %s", shown, tg.kind == KIND_REGULAR ||
			tg.kind == KIND_NEW ? "cannot rename into place" : "not replaced", strerror(t->io_errno));
		t->failed = 1;
		io_file_discard(t);
	}
	free(tg.path);
	return rc;
}

void io_file_discard(io_transport_t *t)
{
	if (!t->tmp)
		return;
	sigset_t old;
	io_signals_block(&old);
	unlink(t->tmp);
	io_temp_drop(t->live);
	io_signals_restore(&old);
	free(t->tmp);
	t->tmp = NULL;
}
