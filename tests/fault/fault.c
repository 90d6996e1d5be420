/* fault.c: an LD_PRELOAD library that makes the Nth allocation or the Nth output write fail, and counts both in a clean run.
 *
 * Environment:
 *   LOCUS_FAULT_ALLOC=N          the Nth call of malloc, calloc, realloc, posix_memalign,
 *                                aligned_alloc or memalign returns NULL with ENOMEM (strdup,
 *                                fopen and the rest of the C library allocate through these)
 *   LOCUS_FAULT_WRITE=N:KIND     the Nth write to any descriptor but 2 (write, writev, pwrite,
 *                                and the stdio calls on any stream but stderr) fails with
 *                                KIND = ENOSPC or EIO (a stdio call then sets the stream's error
 *                                flag, as a failed flush does), or (KIND = SHORT) write, writev or
 *                                pwrite writes only part of the bytes, which is not an error: the
 *                                caller must write the rest (stdio does that itself: untouched)
 *   LOCUS_FAULT_COUNT=FILE       at exit, append "alloc A write W" (calls seen) to FILE
 *   LOCUS_FAULT_TRACE=1          print a backtrace on stderr where the fault is injected
 * Calls are counted from the library's constructor on, across threads. Test code only (tests/fault).
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <execinfo.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/uio.h>
#include <unistd.h>

/* glibc's own allocator entry points (no dlsym needed, which would allocate) */
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
extern void *__libc_memalign(size_t, size_t);

#define ERR_SEEN 0x0020           /* glibc's _IO_ERR_SEEN: what ferror() reports */

static unsigned long alloc_at, write_at;      /* 0: no fault */
static int write_kind;                        /* 0 ENOSPC, 1 EIO, 2 SHORT */
static unsigned long n_alloc, n_write;
static int ready;
static const char *count_file;
static int trace;

/* With LOCUS_FAULT_TRACE, where the fault happens (for finding the code that mishandles it). */
static void trace_here(void)
{
	void *pc[32];
	if (trace) {
		int n = backtrace(pc, 32);
		backtrace_symbols_fd(pc, n, 2);
	}
}

static ssize_t (*real_write)(int, const void *, size_t);
static ssize_t (*real_writev)(int, const struct iovec *, int);
static ssize_t (*real_pwrite)(int, const void *, size_t, off_t);
static size_t (*real_fwrite)(const void *, size_t, size_t, FILE *);
static int (*real_vfprintf)(FILE *, const char *, va_list);
static int (*real_fputs)(const char *, FILE *);
static int (*real_fputc)(int, FILE *);

static void count_report(void)
{
	char line[96];
	int fd, n;
	if (!count_file)
		return;
	n = snprintf(line, sizeof line, "alloc %lu write %lu\n", n_alloc, n_write);
	fd = open(count_file, O_WRONLY | O_CREAT | O_APPEND, 0644);
	if (fd >= 0) {
		if (real_write)
			real_write(fd, line, (size_t)n);
		close(fd);
	}
}

__attribute__((constructor)) static void fault_init(void)
{
	const char *a = getenv("LOCUS_FAULT_ALLOC"), *w = getenv("LOCUS_FAULT_WRITE");
	real_write = (ssize_t (*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
	real_writev = (ssize_t (*)(int, const struct iovec *, int))dlsym(RTLD_NEXT, "writev");
	real_pwrite = (ssize_t (*)(int, const void *, size_t, off_t))dlsym(RTLD_NEXT, "pwrite");
	real_fwrite = (size_t (*)(const void *, size_t, size_t, FILE *))dlsym(RTLD_NEXT, "fwrite");
	real_vfprintf = (int (*)(FILE *, const char *, va_list))dlsym(RTLD_NEXT, "vfprintf");
	real_fputs = (int (*)(const char *, FILE *))dlsym(RTLD_NEXT, "fputs");
	real_fputc = (int (*)(int, FILE *))dlsym(RTLD_NEXT, "fputc");
	if (a)
		alloc_at = strtoul(a, NULL, 10);
	if (w) {
		const char *k = strchr(w, ':');
		write_at = strtoul(w, NULL, 10);
		write_kind = !k || !strcmp(k + 1, "ENOSPC") ? 0 : !strcmp(k + 1, "EIO") ? 1 : 2;
	}
	count_file = getenv("LOCUS_FAULT_COUNT");
	trace = getenv("LOCUS_FAULT_TRACE") != NULL;
	if (trace) {   /* backtrace() loads libgcc on first use: do it before counting */
		void *pc[2];
		backtrace(pc, 2);
	}
	if (count_file)
		atexit(count_report);
	n_alloc = n_write = 0;
	ready = 1;
}

/* 1 when this allocation is the one to fail. */
static int alloc_fails(void)
{
	if (!ready)
		return 0;
	unsigned long k = __atomic_add_fetch(&n_alloc, 1, __ATOMIC_RELAXED);
	if (k == alloc_at) {
		trace_here();
		errno = ENOMEM;
		return 1;
	}
	return 0;
}

/* For a write of n bytes to fd: -1 to fail (errno set), 0 to write all, else the bytes to write. */
static long write_fault(int fd, size_t n)
{
	if (!ready || fd == 2 || n == 0)
		return 0;
	unsigned long k = __atomic_add_fetch(&n_write, 1, __ATOMIC_RELAXED);
	if (k != write_at)
		return 0;
	trace_here();
	if (write_kind == 2)
		return n > 1 ? (long)(n / 2) : 0;
	errno = write_kind == 0 ? ENOSPC : EIO;
	return -1;
}

void *malloc(size_t n)
{
	return alloc_fails() ? NULL : __libc_malloc(n);
}

void *calloc(size_t m, size_t n)
{
	return alloc_fails() ? NULL : __libc_calloc(m, n);
}

void *realloc(void *p, size_t n)
{
	return alloc_fails() ? NULL : __libc_realloc(p, n);
}

int posix_memalign(void **out, size_t align, size_t n)
{
	if (alloc_fails())
		return ENOMEM;
	void *p = __libc_memalign(align, n);
	if (!p)
		return ENOMEM;
	*out = p;
	return 0;
}

void *aligned_alloc(size_t align, size_t n)
{
	return alloc_fails() ? NULL : __libc_memalign(align, n);
}

void *memalign(size_t align, size_t n)
{
	return alloc_fails() ? NULL : __libc_memalign(align, n);
}

ssize_t write(int fd, const void *buf, size_t n)
{
	long f = write_fault(fd, n);
	if (f < 0)
		return -1;
	return real_write(fd, buf, f ? (size_t)f : n);
}

ssize_t pwrite(int fd, const void *buf, size_t n, off_t off)
{
	long f = write_fault(fd, n);
	if (f < 0)
		return -1;
	return real_pwrite(fd, buf, f ? (size_t)f : n, off);
}

ssize_t writev(int fd, const struct iovec *iov, int cnt)
{
	size_t n = 0;
	for (int i = 0; i < cnt; i++)
		n += iov[i].iov_len;
	long f = write_fault(fd, n);
	if (f < 0)
		return -1;
	if (f && cnt > 0)   /* a short writev: part of the first buffer */
		return real_write(fd, iov[0].iov_base, iov[0].iov_len < (size_t)f ? iov[0].iov_len : (size_t)f);
	return real_writev(fd, iov, cnt);
}

/* The fault of a stdio call on f of n bytes: as write_fault, except that SHORT does not apply
 * (stdio writes the rest itself: a short fwrite is an error, never a partial success). */
static long stdio_fault(FILE *f, size_t n)
{
	if (write_kind == 2)
		return 0;
	return write_fault(fileno(f), n) < 0 ? -1 : 0;
}

/* A failed stdio call: the stream's error flag is set, as a failed flush would set it. */
static void stream_fails(FILE *f)
{
	f->_flags |= ERR_SEEN;
}

size_t fwrite(const void *buf, size_t size, size_t nmemb, FILE *f)
{
	if (size && nmemb && stdio_fault(f, size * nmemb) < 0) {
		stream_fails(f);
		return 0;
	}
	return real_fwrite(buf, size, nmemb, f);
}

int fputs(const char *s, FILE *f)
{
	if (stdio_fault(f, strlen(s)) < 0) {
		stream_fails(f);
		return EOF;
	}
	return real_fputs(s, f);
}

int fputc(int c, FILE *f)
{
	if (stdio_fault(f, 1) < 0) {
		stream_fails(f);
		return EOF;
	}
	return real_fputc(c, f);
}

int putc(int c, FILE *f)
{
	return fputc(c, f);
}

int putchar(int c)
{
	return fputc(c, stdout);
}

int puts(const char *s)
{
	if (fputs(s, stdout) == EOF)
		return EOF;
	return fputc('\n', stdout);
}

int vfprintf(FILE *f, const char *fmt, va_list ap)
{
	if (stdio_fault(f, 1) < 0) {
		stream_fails(f);
		return -1;
	}
	return real_vfprintf(f, fmt, ap);
}

int fprintf(FILE *f, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	int r = vfprintf(f, fmt, ap);
	va_end(ap);
	return r;
}

int vprintf(const char *fmt, va_list ap)
{
	return vfprintf(stdout, fmt, ap);
}

int printf(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	int r = vfprintf(stdout, fmt, ap);
	va_end(ap);
	return r;
}
