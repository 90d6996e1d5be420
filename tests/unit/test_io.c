/* test_io.c: the transport's output path: io_printf, signals and exit removing temporaries,
 * ignored signals respected, page targets chosen late, errors naming the cause, sockets. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>
#include "io/transport.h"
#include "unit.h"

static char dir[256];
static io_transport_t *exit_kept;

/* Entries of dir other than . and .. */
static int entries(void)
{
	int n = 0;
	DIR *d = opendir(dir);
	for (struct dirent *e; d && (e = readdir(d));)
		n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
	if (d)
		closedir(d);
	return n;
}

static void empty_dir(void)
{
	DIR *d = opendir(dir);
	char p[600];
	for (struct dirent *e; d && (e = readdir(d));) {
		if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
			continue;
		snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
		if (unlink(p) < 0)
			rmdir(p);
	}
	if (d)
		closedir(d);
}

static char *slurp(const char *path, size_t *n)
{
	FILE *f = fopen(path, "rb");
	char *b = NULL;
	*n = 0;
	if (f && fseek(f, 0, SEEK_END) == 0) {
		long len = ftell(f);
		rewind(f);
		b = malloc((size_t)len + 1);
		if (b && fread(b, 1, (size_t)len, f) == (size_t)len)
			*n = (size_t)len;
	}
	if (f)
		fclose(f);
	return b;
}

static void test_printf(void)
{
	char err[600], path[400];
	snprintf(path, sizeof path, "%s/p.txt", dir);
	io_transport_t *t = io_open_write(path, err, sizeof err);
	CHECK(t != NULL, "open %s", t ? "" : err);
	if (!t)
		return;
	/* many lines across the 64 KiB buffer boundary, then one result longer than the buffer */
	size_t cap = 4u << 20, len = 0;
	char *want = malloc(cap), *big = malloc(200001);
	memset(big, 'x', 200000);
	big[200000] = 0;
	int rc = 0;
	for (int k = 0; k < 20000; k++) {
		rc |= io_printf(t, "line %d: %s %.3f\n", k, k % 7 ? "seven" : "", k / 3.0);
		len += (size_t)snprintf(want + len, cap - len, "line %d: %s %.3f\n", k, k % 7 ? "seven" : "", k / 3.0);
	}
	rc |= io_printf(t, "[%s]", big);
	len += (size_t)snprintf(want + len, cap - len, "[%s]", big);
	rc |= io_write(t, "end\n", 4);
	len += (size_t)snprintf(want + len, cap - len, "end\n");
	CHECK(rc == 0, "io_printf and io_write succeed");
	CHECK(io_close(t, IO_COMMIT) == 0, "commit");
	size_t n;
	char *got = slurp(path, &n);
	CHECK(got && n == len && memcmp(got, want, n) == 0, "io_printf bytes = snprintf bytes (%zu of %zu)", n, len);
	free(got);
	free(want);
	free(big);
	empty_dir();
}

/* A child opens outputs (one kept as a finished page, one being written), says so on fd w,
 * and waits for the signal. */
static void child_outputs(int w, int ignore_hup)
{
	char err[600], path[400];
	if (ignore_hup)
		signal(SIGHUP, SIG_IGN);   /* before this process's first output: nohup */
	snprintf(path, sizeof path, "%s/page.png", dir);
	io_transport_t *a = io_open_write(path, err, sizeof err), *b = io_open_write(path, err, sizeof err);
	if (!a || !b || io_write(a, "one", 3) || io_close(a, IO_KEEP) || io_printf(b, "two %d", 2) || io_flush(b))
		_exit(9);
	if (write(w, "r", 1) != 1)
		_exit(9);
	for (;;)
		pause();
}

static void test_signal(int sig, int ignore_hup)
{
	int p[2];
	if (pipe(p) < 0)
		return;
	fflush(stdout);
	pid_t pid = fork();
	if (pid == 0) {
		close(p[0]);
		child_outputs(p[1], ignore_hup);
	}
	close(p[1]);
	char c = 0;
	int ready = read(p[0], &c, 1) == 1;
	close(p[0]);
	CHECK(ready && entries() == 2, "the child holds two temporaries (%d entries)", entries());
	int status = 0;
	if (ignore_hup) {
		kill(pid, SIGHUP);
		usleep(100000);
		CHECK(waitpid(pid, &status, WNOHANG) == 0 && entries() == 2, "an ignored SIGHUP stays ignored");
	}
	kill(pid, sig);
	waitpid(pid, &status, 0);
	CHECK(WIFSIGNALED(status) && WTERMSIG(status) == sig, "the child dies of signal %d (status %d)", sig,
		WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status));
	CHECK(entries() == 0, "signal %d removed every temporary (%d left)", sig, entries());
	empty_dir();
}

static void test_exit(void)
{
	fflush(stdout);
	pid_t pid = fork();
	if (pid == 0) {
		char err[600], path[400];
		snprintf(path, sizeof path, "%s/e.meta", dir);
		exit_kept = io_open_write(path, err, sizeof err);   /* global: no leak report */
		if (!exit_kept || io_write(exit_kept, "x", 1) || io_flush(exit_kept))
			_exit(9);
		exit(3);   /* a program that exits with an output open */
	}
	int status = 0;
	waitpid(pid, &status, 0);
	CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 3 && entries() == 0, "exit() removes the temporaries");
	/* a forked child that exits leaves its parent's temporaries alone */
	char err[600], path[400];
	snprintf(path, sizeof path, "%s/parent.meta", dir);
	io_transport_t *t = exit_kept = io_open_write(path, err, sizeof err);   /* global: no leak report */
	fflush(stdout);
	if (t && (pid = fork()) == 0)
		exit(0);
	waitpid(pid, &status, 0);
	CHECK(t && entries() == 1 && io_close(t, IO_COMMIT) == 0 && access(path, F_OK) == 0,
		"a forked child's exit() leaves the parent's temporary, which commits");
	empty_dir();
}

static void test_late_target(void)
{
	char err[600] = "", path[400], page[400], sub[400];
	snprintf(path, sizeof path, "%s/m.png", dir);
	snprintf(page, sizeof page, "%s/m-001.png", dir);
	snprintf(sub, sizeof sub, "%s/m-002.png", dir);
	/* an existing page file keeps its mode */
	int fd = open(page, O_WRONLY | O_CREAT, 0600);
	if (fd >= 0)
		close(fd);
	chmod(page, 0640);
	io_transport_t *t = io_open_write(path, err, sizeof err);
	CHECK(t && io_write(t, "p1", 2) == 0 && io_close(t, IO_KEEP) == 0, "page 1 kept");
	struct stat st;
	CHECK(t && io_finish(t, 1, page, err, sizeof err) == 0 && stat(page, &st) == 0 && (st.st_mode & 0777) == 0640,
		"a page name chosen late keeps the mode of the file it replaces");
	/* a directory in the way: one line, the temporary removed */
	mkdir(sub, 0755);
	t = io_open_write(path, err, sizeof err);
	CHECK(t && io_close(t, IO_KEEP) == 0, "page 2 kept");
	err[0] = 0;
	CHECK(t && io_finish(t, 1, sub, err, sizeof err) < 0 && strstr(err, "m-002.png") && strstr(err, "Is a directory")
		&& entries() == 2, "a directory at the page name: refused with '%s', nothing left", err);
	empty_dir();
}

static void test_errors(void)
{
	char err[600], path[400];
	snprintf(path, sizeof path, "%s/fifo", dir);
	mkfifo(path, 0600);
	int rd = open(path, O_RDONLY | O_NONBLOCK);
	signal(SIGPIPE, SIG_IGN);
	io_transport_t *t = io_open_write(path, err, sizeof err);
	CHECK(t && io_in_place(t), "a FIFO is written in place");
	close(rd);   /* the reader goes away */
	if (t) {
		int rc = io_write(t, "abc", 3) || io_flush(t);
		CHECK(rc && strstr(io_error(t), path) && strstr(io_error(t), "Broken pipe"),
			"a write error names the output and the cause: '%s'", io_error(t));
		CHECK(io_printf(t, "more") < 0, "nothing more after a failed write");
		io_close(t, IO_ABORT);
	}
	struct stat st;
	CHECK(lstat(path, &st) == 0 && S_ISFIFO(st.st_mode), "the FIFO is still a FIFO");
	signal(SIGPIPE, SIG_DFL);
	empty_dir();
}

static void test_socket(void)
{
	char err[600], buf[16] = "";
	struct sockaddr_un sa;
	memset(&sa, 0, sizeof sa);
	sa.sun_family = AF_UNIX;
	if (snprintf(sa.sun_path, sizeof sa.sun_path, "%s/sock", dir) >= (int)sizeof sa.sun_path) {
		CHECK(1, "socket # SKIP the scratch directory's name is too long for a socket");
		return;
	}
	int s = socket(AF_UNIX, SOCK_STREAM, 0);
	int up = s >= 0 && bind(s, (struct sockaddr *)&sa, sizeof sa) == 0 && listen(s, 1) == 0;
	CHECK(up, "a listening socket");
	if (!up)
		return;
	io_transport_t *t = io_open_write(sa.sun_path, err, sizeof err);
	CHECK(t && io_in_place(t) && io_printf(t, "hello %d", 7) == 0 && io_close(t, IO_COMMIT) == 0,
		"a socket is written in place %s", t ? "" : err);
	int c = accept(s, NULL, NULL);
	ssize_t n = c >= 0 ? read(c, buf, sizeof buf - 1) : -1;
	CHECK(n == 7 && memcmp(buf, "hello 7", 7) == 0, "the listener reads what was written");
	struct stat st;
	CHECK(lstat(sa.sun_path, &st) == 0 && S_ISSOCK(st.st_mode), "the socket is still a socket");
	if (c >= 0)
		close(c);
	close(s);
	empty_dir();
}

int main(void)
{
	snprintf(dir, sizeof dir, "%s/test_io.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	/* the default actions, whatever started this test (a background job ignores SIGINT) */
	signal(SIGINT, SIG_DFL);
	signal(SIGTERM, SIG_DFL);
	signal(SIGHUP, SIG_DFL);
	test_signal(SIGTERM, 1);   /* first: the child's first output sees SIGHUP ignored */
	test_printf();
	test_signal(SIGINT, 0);    /* the handlers this process installed, inherited by fork */
	test_signal(SIGTERM, 0);
	test_exit();
	test_late_target();
	test_errors();
	test_socket();
	rmdir(dir);
	return UNIT_DONE();
}
