/* SPDX-License-Identifier: MIT */
/*
 * file.c - the hosted platform's files (POSIX): whole-file reads, the tg_io
 * the scene parser loads OBJ meshes through, and atomic writes through a
 * temporary file in the destination's directory + fsync + rename.
 */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>
#include "file.h"

static void say(char *msg, size_t msgsize, const char *fmt, ...)
{
    va_list ap;
    if (!msg || msgsize == 0) return;
    va_start(ap, fmt);
    vsnprintf(msg, msgsize, fmt, ap);
    va_end(ap);
}

/* ---- reading ---- */

int tgp_file_read(const char *path, char **data, size_t *size, char *msg, size_t msgsize)
{
    struct stat st;
    char *buf = NULL;
    size_t cap = 0, len = 0;
    int fd;

    *data = NULL;
    *size = 0;
    fd = open(path, O_RDONLY);
    if (fd < 0) {
        say(msg, msgsize, "cannot open: %s", strerror(errno));
        return 1;
    }
    if (fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
        say(msg, msgsize, "cannot read: it is a directory");
        close(fd);
        return 1;
    }
    /* Read until EOF (works for pipes too), growing the buffer. */
    for (;;) {
        ssize_t n;
        if (cap - len < 2) {
            size_t ncap = cap ? cap * 2 : 65536;
            char *nbuf;
            if (ncap > TG_FILE_MAX_BYTES + 2) ncap = TG_FILE_MAX_BYTES + 2;
            if (ncap - len < 2) {
                say(msg, msgsize, "cannot read: larger than the limit of %lu bytes",
                    (unsigned long)TG_FILE_MAX_BYTES);
                free(buf);
                close(fd);
                return 1;
            }
            nbuf = (char *)realloc(buf, ncap);
            if (!nbuf) {
                say(msg, msgsize, "cannot read: out of memory");
                free(buf);
                close(fd);
                return 1;
            }
            buf = nbuf;
            cap = ncap;
        }
        n = read(fd, buf + len, cap - len - 1);
        if (n < 0) {
            if (errno == EINTR) continue;
            say(msg, msgsize, "cannot read: %s", strerror(errno));
            free(buf);
            close(fd);
            return 1;
        }
        if (n == 0) break;
        len += (size_t)n;
        if (len > TG_FILE_MAX_BYTES) {
            say(msg, msgsize, "cannot read: larger than the limit of %lu bytes",
                (unsigned long)TG_FILE_MAX_BYTES);
            free(buf);
            close(fd);
            return 1;
        }
    }
    close(fd);
    buf[len] = '\0';
    *data = buf;
    *size = len;
    return 0;
}

/* ---- tg_io ---- */

static int host_io_read(void *user, const char *path, const char **data, size_t *size,
                        const char **reason)
{
    tgp_host_io *h = (tgp_host_io *)user;
    (void)reason;
    tgp_host_io_file *node;
    char *buf;
    size_t n;

    if (tgp_file_read(path, &buf, &n, h->last_error, sizeof h->last_error)) return 1;
    node = (tgp_host_io_file *)malloc(sizeof *node);
    if (!node) {
        free(buf);
        say(h->last_error, sizeof h->last_error, "cannot read: out of memory");
        return 1;
    }
    node->data = buf;
    node->next = h->files;
    h->files = node;
    *data = buf;
    *size = n;
    return 0;
}

void tgp_host_io_init(tgp_host_io *h)
{
    h->io.user = h;
    h->io.read_file = host_io_read;
    h->files = NULL;
    h->last_error[0] = '\0';
}

void tgp_host_io_free(tgp_host_io *h)
{
    while (h->files) {
        tgp_host_io_file *next = h->files->next;
        free(h->files->data);
        free(h->files);
        h->files = next;
    }
}

/* ---- atomic output ---- */

/* The temporary file being written, for the signal handler to remove. */
static volatile sig_atomic_t cleanup_armed;
static char cleanup_path[4096];

static void on_fatal_signal(int sig)
{
    if (cleanup_armed) unlink(cleanup_path);
    signal(sig, SIG_DFL);
    raise(sig);
}

void tgp_outfile_remove_on_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_fatal_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    sigaction(SIGPIPE, &sa, NULL);
}

/* Hold off the cleanup signals while a temporary comes into being or is
 * renamed away, so the handler never misses one nor removes a stranger's. */
static void hold_signals(sigset_t *old)
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    sigaddset(&set, SIGPIPE);
    sigprocmask(SIG_BLOCK, &set, old);
}

static void release_signals(const sigset_t *old)
{
    sigprocmask(SIG_SETMASK, old, NULL);
}

static void arm_cleanup(const char *tmp)
{
    size_t n = strlen(tmp);
    cleanup_armed = 0;
    if (n < sizeof cleanup_path) {
        memcpy(cleanup_path, tmp, n + 1);
        cleanup_armed = 1;
    }
}

/* "dir/" part of path (with the slash), or "" */
static size_t dir_length(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? (size_t)(slash - path) + 1 : 0;
}

static char *dup_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = (char *)malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

static void outfile_release(tgp_outfile *f)
{
    if (f->fd >= 0) close(f->fd);
    f->fd = -1;
    cleanup_armed = 0;
    free(f->path);
    free(f->tmp_path);
    f->path = f->tmp_path = NULL;
}

int tgp_outfile_open(tgp_outfile *f, const char *path, char *msg, size_t msgsize)
{
    static unsigned long counter;
    size_t dlen = dir_length(path), plen = strlen(path), tlen;
    sigset_t old;
    int attempt;

    f->fd = -1;
    f->path = f->tmp_path = NULL;
    f->buffered = 0;
    f->failed = 0;
    if (plen == 0 || dlen == plen) {
        say(msg, msgsize, "cannot write: not a file name");
        return 1;
    }
    tlen = plen + 64; /* "." + ".tmp-" + two 20-digit numbers + "-" + NUL */
    f->path = dup_string(path);
    f->tmp_path = (char *)malloc(tlen);
    if (!f->path || !f->tmp_path) {
        say(msg, msgsize, "cannot write: out of memory");
        outfile_release(f);
        return 1;
    }
    hold_signals(&old);
    for (attempt = 0; attempt < 100; attempt++) {
        /* dir/.name.tmp-PID-N: same directory, so rename() is atomic */
        snprintf(f->tmp_path, tlen, "%.*s.%s.tmp-%ld-%lu", (int)dlen, path, path + dlen,
                 (long)getpid(), counter++);
        f->fd = open(f->tmp_path, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (f->fd >= 0 || errno != EEXIST) break;
    }
    if (f->fd < 0) {
        int e = errno;
        release_signals(&old);
        say(msg, msgsize, "cannot write: %s", strerror(e));
        outfile_release(f);
        return 1;
    }
    arm_cleanup(f->tmp_path);
    release_signals(&old);
    return 0;
}

static void outfile_flush(tgp_outfile *f)
{
    size_t done = 0;
    while (done < f->buffered && !f->failed) {
        ssize_t n = write(f->fd, f->buf + done, f->buffered - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            f->failed = errno ? errno : EIO;
        } else {
            done += (size_t)n;
        }
    }
    f->buffered = 0;
}

void tgp_outfile_write(tgp_outfile *f, const void *data, size_t n)
{
    const unsigned char *p = (const unsigned char *)data;
    if (f->fd < 0 || f->failed) return;
    while (n > 0) {
        size_t room = sizeof f->buf - f->buffered, take = n < room ? n : room;
        memcpy(f->buf + f->buffered, p, take);
        f->buffered += take;
        p += take;
        n -= take;
        if (f->buffered == sizeof f->buf) outfile_flush(f);
        if (f->failed) return;
    }
}

static void sync_directory(const char *path)
{
    size_t dlen = dir_length(path);
    char dir[4096];
    int fd;
    if (dlen == 0) snprintf(dir, sizeof dir, ".");
    else if (dlen < sizeof dir) snprintf(dir, sizeof dir, "%.*s", (int)dlen, path);
    else return;
    fd = open(dir, O_RDONLY);
    if (fd < 0) return;
    fsync(fd); /* best effort: some file systems refuse fsync on directories */
    close(fd);
}

int tgp_outfile_commit(tgp_outfile *f, char *msg, size_t msgsize)
{
    sigset_t old;
    int err = 0;
    if (f->fd < 0) {
        say(msg, msgsize, "cannot write: file not open");
        return 1;
    }
    outfile_flush(f);
    if (f->failed) err = f->failed;
    else if (fsync(f->fd) != 0 && errno != EINVAL && errno != EROFS) err = errno;
    if (close(f->fd) != 0 && !err) err = errno ? errno : EIO;
    f->fd = -1;
    hold_signals(&old);
    if (!err && rename(f->tmp_path, f->path) != 0) err = errno ? errno : EIO;
    if (err) {
        unlink(f->tmp_path);
        outfile_release(f);
        release_signals(&old);
        say(msg, msgsize, "cannot write: %s", strerror(err));
        return 1;
    }
    cleanup_armed = 0;
    release_signals(&old);
    sync_directory(f->path);
    outfile_release(f);
    return 0;
}

void tgp_outfile_abort(tgp_outfile *f)
{
    sigset_t old;
    hold_signals(&old);
    if (f->tmp_path && (f->fd >= 0 || cleanup_armed)) unlink(f->tmp_path);
    outfile_release(f);
    release_signals(&old);
}

tgp_outfile *tgp_outfile_create(const char *path, char *msg, size_t msgsize)
{
    tgp_outfile *f = (tgp_outfile *)malloc(sizeof *f);
    if (!f) {
        say(msg, msgsize, "cannot write: out of memory");
        return NULL;
    }
    if (tgp_outfile_open(f, path, msg, msgsize)) {
        free(f);
        return NULL;
    }
    return f;
}

int tgp_outfile_finish(tgp_outfile *f, char *msg, size_t msgsize)
{
    int r = tgp_outfile_commit(f, msg, msgsize);
    free(f);
    return r;
}

int tgp_file_write_atomic(const char *path, const void *data, size_t size,
                         char *msg, size_t msgsize)
{
    tgp_outfile *f = tgp_outfile_create(path, msg, msgsize);
    if (!f) return 1;
    tgp_outfile_write(f, data, size);
    return tgp_outfile_finish(f, msg, msgsize);
}

int tgp_file_dir_writable(const char *path, char *msg, size_t msgsize)
{
    size_t dlen = dir_length(path);
    char dir[4096];
    struct stat st;
    if (dlen == 0) snprintf(dir, sizeof dir, ".");
    else if (dlen < sizeof dir) snprintf(dir, sizeof dir, "%.*s", (int)dlen, path);
    else {
        say(msg, msgsize, "cannot write: path too long");
        return 1;
    }
    if (stat(dir, &st) != 0) {
        say(msg, msgsize, "cannot write: directory '%s': %s", dir, strerror(errno));
        return 1;
    }
    if (!S_ISDIR(st.st_mode)) {
        say(msg, msgsize, "cannot write: '%s' is not a directory", dir);
        return 1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        say(msg, msgsize, "cannot write: directory '%s': %s", dir, strerror(errno));
        return 1;
    }
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        say(msg, msgsize, "cannot write: it is a directory");
        return 1;
    }
    return 0;
}
