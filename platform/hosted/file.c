/* SPDX-License-Identifier: MIT */
/*
 * file.c - the hosted platform's files (POSIX): whole-file reads of regular
 * files within a size limit, the tg_io the scene parser loads OBJ meshes
 * through, and atomic writes through a temporary file in the destination's
 * directory + fsync + rename (what is checked: file.h).
 */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>
#include "file.h"

/* printf into msg (msgsize bytes, cut to fit); nothing when msg is NULL. */
void tgp_say(char *msg, size_t msgsize, const char *fmt, ...)
{
    va_list ap;
    if (!msg || msgsize == 0) return;
    va_start(ap, fmt);
    vsnprintf(msg, msgsize, fmt, ap);
    va_end(ap);
}

/* ---- reading ---- */

/* strerror's text with a lower-case first letter: "no such file or directory" */
static void errno_text(int e, char *buf, size_t size)
{
    tgp_say(buf, size, "%s", strerror(e));
    if (size && buf[0] >= 'A' && buf[0] <= 'Z') buf[0] = (char)(buf[0] - 'A' + 'a');
}

/* Whose fault an errno is: the machine's (out of memory, I/O) or the input's. */
static int errno_status(int e)
{
    return e == ENOMEM || e == EMFILE || e == ENFILE || e == EIO ? TG_ERR_RUNTIME : TG_ERR_INPUT;
}

void tgp_bytes_text(size_t bytes, char *buf, size_t size)
{
    static const char *const unit[] = { "GiB", "MiB", "KiB" };
    int i;
    for (i = 0; i < 3; i++) {
        size_t u = (size_t)1 << (30 - 10 * i);
        if (bytes >= u && bytes % u == 0) {
            tgp_say(buf, size, "%lu %s", (unsigned long)(bytes / u), unit[i]);
            return;
        }
    }
    tgp_say(buf, size, "%lu bytes", (unsigned long)bytes);
}

static int too_large(size_t limit, char *msg, size_t msgsize)
{
    char text[64];
    tgp_bytes_text(limit, text, sizeof text);
    tgp_say(msg, msgsize, "larger than the %s limit", text);
    return TG_ERR_INPUT;
}

/* Open `path` for reading if it is a regular file no larger than `limit`
 * (O_NONBLOCK: a FIFO without a writer does not block the open). */
static int open_regular(const char *path, size_t limit, struct stat *st, char *msg, size_t msgsize)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY), flags, e;
    if (fd < 0) {
        e = errno;
        errno_text(e, msg, msgsize);
        return -errno_status(e);
    }
    if (fstat(fd, st) != 0) {
        e = errno;
        errno_text(e, msg, msgsize);
        close(fd);
        return -TG_ERR_RUNTIME;
    }
    e = 0;
    if (S_ISDIR(st->st_mode)) tgp_say(msg, msgsize, "is a directory"), e = TG_ERR_INPUT;
    else if (!S_ISREG(st->st_mode)) tgp_say(msg, msgsize, "not a regular file"), e = TG_ERR_INPUT;
    else if (st->st_size < 0 || (uintmax_t)st->st_size > (uintmax_t)limit) e = too_large(limit, msg, msgsize);
    flags = fcntl(fd, F_GETFL);
    if (!e && flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    if (e) {
        close(fd);
        return -e;
    }
    return fd;
}

/* Read fd to its end, at most limit bytes, into a buffer of `cap` bytes to
 * start with (grown as needed) plus a NUL.  0 or a tg_status. */
static int read_all(int fd, size_t limit, size_t cap, char **data, size_t *size,
                    char *msg, size_t msgsize)
{
    char *buf = NULL;
    size_t len = 0;
    for (;;) {
        ssize_t n;
        if (!buf || len + 1 == cap) {
            size_t ncap = !buf ? cap : cap <= (limit + 2) / 2 ? cap * 2 : limit + 2;
            char *nbuf;
            if (buf && ncap <= cap) break; /* cannot happen: len > limit stops first */
            nbuf = (char *)realloc(buf, ncap);
            if (!nbuf) {
                free(buf);
                tgp_say(msg, msgsize, "out of memory (%lu bytes)", (unsigned long)ncap);
                return TG_ERR_RUNTIME;
            }
            buf = nbuf;
            cap = ncap;
        }
        n = read(fd, buf + len, cap - 1 - len);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            int e = errno;
            free(buf);
            errno_text(e, msg, msgsize);
            return errno_status(e);
        }
        if (n == 0) break;
        len += (size_t)n;
        if (len > limit) {
            free(buf);
            return too_large(limit, msg, msgsize);
        }
    }
    buf[len] = '\0';
    *data = buf;
    *size = len;
    return 0;
}

int tgp_file_read_limited(const char *path, size_t limit, char **data, size_t *size,
                          tgp_file_id *id, char *msg, size_t msgsize)
{
    struct stat st;
    size_t cap;
    int fd, r;
    *data = NULL;
    *size = 0;
    if (limit > (size_t)-1 / 2) limit = (size_t)-1 / 2;
    fd = open_regular(path, limit, &st, msg, msgsize);
    if (fd < 0) return -fd;
    /* the size it has, one byte to see it end and the NUL; files that say
     * 0 (/proc) start small */
    cap = st.st_size > 0 ? (size_t)st.st_size + 2 : 4096;
    if (cap > limit + 2) cap = limit + 2;
    r = read_all(fd, limit, cap, data, size, msg, msgsize);
    close(fd);
    if (!r && id) {
        id->dev = st.st_dev;
        id->ino = st.st_ino;
    }
    return r;
}

int tgp_file_read(const char *path, char **data, size_t *size, char *msg, size_t msgsize)
{
    char why[200];
    int r = tgp_file_read_limited(path, (size_t)TG_MAX_FILE_BYTES, data, size, NULL, why, sizeof why);
    if (r) tgp_say(msg, msgsize, "cannot read: %s", why);
    return r;
}

int tgp_file_identify(const char *path, tgp_file_id *id)
{
    struct stat st;
    if (stat(path, &st) != 0) return 1;
    id->dev = st.st_dev;
    id->ino = st.st_ino;
    return 0;
}

int tgp_file_is(const char *path, const tgp_file_id *id)
{
    tgp_file_id other;
    return tgp_file_identify(path, &other) == 0 && other.dev == id->dev && other.ino == id->ino;
}

/* ---- tg_io ---- */

static char *dup_string(const char *s);

static int host_io_read(void *user, const char *path, const char **data, size_t *size,
                        const char **reason)
{
    tgp_host_io *h = (tgp_host_io *)user;
    tgp_host_io_file *node;
    char *buf;
    size_t n;
    tgp_file_id id;
    int r = tgp_file_read_limited(path, (size_t)TG_MAX_FILE_BYTES, &buf, &n, &id, h->last_error,
                                  sizeof h->last_error);
    node = r ? NULL : (tgp_host_io_file *)malloc(sizeof *node);
    if (!r && (!node || !(node->path = dup_string(path)))) {
        free(buf);
        free(node);
        tgp_say(h->last_error, sizeof h->last_error, "out of memory");
        r = TG_ERR_RUNTIME;
    }
    if (r) {
        h->last_status = r;
        if (reason) *reason = h->last_error;
        return 1;
    }
    node->data = buf;
    node->id = id;
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
    h->last_status = 0;
}

void tgp_host_io_free(tgp_host_io *h)
{
    while (h->files) {
        tgp_host_io_file *next = h->files->next;
        free(h->files->data);
        free(h->files->path);
        free(h->files);
        h->files = next;
    }
    h->last_error[0] = '\0';
    h->last_status = 0;
}

/* ---- atomic output ---- */

#if !defined(PATH_MAX)
#define PATH_MAX 4096
#endif
#define TMP_MARK ".tinygi-tmp-"   /* ".NAME" TMP_MARK "PID-N" */
#define TMP_TRIES 100             /* N is 0..99 */
/* "." + TMP_MARK + a 10-digit PID + "-" + 2 digits */
#define TMP_EXTRA (1 + sizeof TMP_MARK - 1 + 10 + 1 + 2)
#define MAX_LINK_HOPS 40          /* symbolic links followed, as Linux's ELOOP */

/* The temporary file being written, for the signal handler to remove. */
static volatile sig_atomic_t cleanup_armed;
static char cleanup_path[PATH_MAX + 64];

static void on_fatal_signal(int sig)
{
    if (cleanup_armed) unlink(cleanup_path);
    signal(sig, SIG_DFL);
    raise(sig);
}

void tgp_outfile_remove_on_signals(void)
{
    static const int sigs[] = { SIGINT, SIGTERM, SIGHUP, SIGPIPE };
    struct sigaction sa, old;
    size_t i;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_fatal_signal;
    sigemptyset(&sa.sa_mask);
    for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        /* nohup and `cmd &` hand us SIGHUP / SIGINT ignored: keep it so */
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        sigaction(sigs[i], &sa, NULL);
    }
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

/* The directory part of path ("." for none) into dir[PATH_MAX]. */
static void dir_of(const char *path, char *dir)
{
    size_t dlen = dir_length(path);
    if (dlen == 0) snprintf(dir, PATH_MAX, ".");
    else snprintf(dir, PATH_MAX, "%.*s", (int)dlen, path);
}

/* The file a write to `path` replaces: symbolic links followed, as open()
 * follows them.  A malloc'd path, or NULL with errno set. */
static char *follow_links(const char *path, struct stat *st, int *exists)
{
    char *cur = dup_string(path), link[PATH_MAX];
    int hops;
    for (hops = 0; cur; hops++) {
        ssize_t n;
        size_t dlen;
        char *next;
        if (lstat(cur, st) != 0) {
            if (errno == ENOENT) break;
            free(cur);
            return NULL;
        }
        if (!S_ISLNK(st->st_mode)) {
            *exists = 1;
            return cur;
        }
        n = readlink(cur, link, sizeof link);
        if (n < 0 || (size_t)n >= sizeof link || hops == MAX_LINK_HOPS) {
            if (n >= 0) errno = hops == MAX_LINK_HOPS ? ELOOP : ENAMETOOLONG;
            free(cur);
            return NULL;
        }
        link[n] = '\0';
        dlen = link[0] == '/' ? 0 : dir_length(cur); /* relative: from the link's directory */
        next = (char *)malloc(dlen + (size_t)n + 1);
        if (next) {
            memcpy(next, cur, dlen);
            memcpy(next + dlen, link, (size_t)n + 1);
        }
        free(cur);
        cur = next;
    }
    if (!cur) errno = ENOMEM;
    *exists = 0;
    return cur;
}

/* Where an output goes, checked: the file replaced and what is there now. */
typedef struct out_target {
    char *path;         /* links followed (malloc'd) */
    int exists;
    struct stat st;     /* when it exists */
    size_t keep;        /* bytes of the name kept in the temporary's name */
} out_target;

static int out_fail(int status, char *msg, size_t msgsize, const char *what, const char *detail)
{
    tgp_say(msg, msgsize, "cannot write: %s%s%s", what, detail ? ": " : "", detail ? detail : "");
    return status;
}

/* The directory must exist and take new files; the name must fit. */
static int target_check_names(out_target *t, char *msg, size_t msgsize)
{
    char dir[PATH_MAX], why[128], what[PATH_MAX + 32];
    size_t dlen = dir_length(t->path), nlen = strlen(t->path) - dlen;
    struct stat st;
    long name_max;
    if (dlen >= PATH_MAX) return out_fail(TG_ERR_INPUT, msg, msgsize, "path too long", NULL);
    dir_of(t->path, dir);
    snprintf(what, sizeof what, "directory '%s'", dir);
    if (stat(dir, &st) != 0) {
        errno_text(errno, why, sizeof why);
        return out_fail(TG_ERR_RUNTIME, msg, msgsize, what, why);
    }
    if (!S_ISDIR(st.st_mode)) return out_fail(TG_ERR_RUNTIME, msg, msgsize, what, "not a directory");
    if (access(dir, W_OK | X_OK) != 0) {
        errno_text(errno, why, sizeof why);
        return out_fail(TG_ERR_RUNTIME, msg, msgsize, what, why);
    }
    /* (a name longer than the file system allows failed lstat: ENAMETOOLONG) */
    name_max = pathconf(dir, _PC_NAME_MAX);
    if (name_max < (long)TMP_EXTRA + 1) name_max = 255;
    t->keep = nlen < (size_t)name_max - TMP_EXTRA ? nlen : (size_t)name_max - TMP_EXTRA;
    while (t->keep > 0 && ((unsigned char)t->path[dlen + t->keep] & 0xC0) == 0x80)
        t->keep--; /* do not cut a UTF-8 character */
    if (dlen + (nlen > t->keep + TMP_EXTRA ? nlen : t->keep + TMP_EXTRA) >= PATH_MAX)
        return out_fail(TG_ERR_INPUT, msg, msgsize, "path too long", NULL);
    return 0;
}

/* 0 with *t filled, or a tg_status with the reason in msg. */
static int target_prepare(const char *path, out_target *t, char *msg, size_t msgsize)
{
    size_t plen = strlen(path);
    char why[128];
    int r;
    memset(t, 0, sizeof *t);
    if (plen == 0 || path[plen - 1] == '/')
        return out_fail(TG_ERR_INPUT, msg, msgsize, "not a file name", NULL);
    if (plen >= PATH_MAX) return out_fail(TG_ERR_INPUT, msg, msgsize, "path too long", NULL);
    t->path = follow_links(path, &t->st, &t->exists);
    if (!t->path) {
        int e = errno;
        errno_text(e, why, sizeof why);
        return out_fail(e == ENAMETOOLONG ? TG_ERR_INPUT : TG_ERR_RUNTIME, msg, msgsize, why, NULL);
    }
    r = target_check_names(t, msg, msgsize);
    if (!r && t->exists) {
        if (S_ISDIR(t->st.st_mode)) r = out_fail(TG_ERR_RUNTIME, msg, msgsize, "it is a directory", NULL);
        else if (!S_ISREG(t->st.st_mode))
            r = out_fail(TG_ERR_RUNTIME, msg, msgsize, "not a regular file", NULL);
        else if (!(t->st.st_mode & 0222) || access(t->path, W_OK) != 0)
            r = out_fail(TG_ERR_RUNTIME, msg, msgsize, "the existing file is read-only "
                         "(make it writable or remove it first)", NULL);
    }
    if (r) {
        free(t->path);
        t->path = NULL;
    }
    return r;
}

int tgp_outfile_check(const char *path, char *msg, size_t msgsize)
{
    out_target t;
    int r = target_prepare(path, &t, msg, msgsize);
    free(t.path);
    return r;
}

/* PID of a temporary named ".NAME" TMP_MARK "PID-N", or 0 if the name is not one. */
static long temporary_pid(const char *name)
{
    const char *mark = NULL, *p, *q;
    long pid = 0;
    if (name[0] != '.') return 0;
    for (p = name + 1; (q = strstr(p, TMP_MARK)) != NULL; p = q + 1) mark = q;
    if (!mark) return 0;
    for (p = mark + sizeof TMP_MARK - 1; *p >= '0' && *p <= '9' && pid < 214748364L; p++)
        pid = pid * 10 + (*p - '0'); /* at most 2^31 - 9: fits a 32-bit long */
    if (*p++ != '-' || !(*p >= '0' && *p <= '9')) return 0;
    while (*p >= '0' && *p <= '9') p++;
    return *p ? 0 : pid;
}

/* A temporary whose writer is gone: its process does not exist, it is ours
 * and no one holds its lock. */
static int temporary_is_stale(const char *path, long pid)
{
    struct stat st;
    struct flock fl;
    int fd, stale;
    if (pid <= 0 || pid == (long)getpid() || (pid_t)pid != pid) return 0;
    if (kill((pid_t)pid, 0) == 0 || errno != ESRCH) return 0;
    fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) return 0;
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    stale = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == geteuid() &&
            fcntl(fd, F_GETLK, &fl) == 0 && fl.l_type == F_UNLCK;
    close(fd);
    return stale;
}

int tgp_outfile_remove_stale(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char path[PATH_MAX + 256];
    int removed = 0;
    if (!d) return 0;
    while ((e = readdir(d)) != NULL) {
        long pid = temporary_pid(e->d_name);
        if (!pid) continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (temporary_is_stale(path, pid) && unlink(path) == 0) removed++;
    }
    closedir(d);
    return removed;
}

/* Once per directory (the last one seen): outputs of one run share it. */
static void remove_stale_once(const char *target)
{
    static char last[PATH_MAX];
    char dir[PATH_MAX];
    dir_of(target, dir);
    if (strcmp(dir, last) == 0) return;
    tgp_outfile_remove_stale(dir);
    memcpy(last, dir, sizeof last);
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

/* Create the temporary for t (O_EXCL, locked, with the mode of the file it
 * replaces); f->tmp_path must hold the name.  0 or an errno. */
static int create_temporary(tgp_outfile *f, const out_target *t, size_t tlen)
{
    size_t dlen = dir_length(t->path);
    struct flock fl;
    int n;
    for (n = 0; n < TMP_TRIES; n++) {
        /* dir/.name.tinygi-tmp-PID-N: same directory, so rename() is atomic */
        snprintf(f->tmp_path, tlen, "%.*s.%.*s%s%ld-%d", (int)dlen, t->path, (int)t->keep,
                 t->path + dlen, TMP_MARK, (long)getpid(), n);
        f->fd = open(f->tmp_path, O_WRONLY | O_CREAT | O_EXCL | O_NOCTTY, 0666);
        if (f->fd >= 0 || errno != EEXIST) break;
    }
    if (f->fd < 0) return errno;
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    fcntl(f->fd, F_SETLK, &fl); /* best effort: tells other hosts it is alive */
    if (t->exists && fchmod(f->fd, t->st.st_mode & 0777) != 0) {
        int e = errno;
        close(f->fd);
        f->fd = -1;
        unlink(f->tmp_path);
        return e;
    }
    return 0;
}

int tgp_outfile_open(tgp_outfile *f, const char *path, char *msg, size_t msgsize)
{
    out_target t;
    size_t tlen;
    sigset_t old;
    int r, e;

    f->fd = -1;
    f->path = f->tmp_path = NULL;
    f->buffered = 0;
    f->failed = 0;
    if ((r = target_prepare(path, &t, msg, msgsize)) != 0) return r;
    remove_stale_once(t.path);
    tlen = strlen(t.path) + TMP_EXTRA + 1;
    f->path = t.path;
    f->tmp_path = (char *)malloc(tlen);
    if (!f->tmp_path) {
        outfile_release(f);
        return out_fail(TG_ERR_RUNTIME, msg, msgsize, "out of memory", NULL);
    }
    hold_signals(&old);
    e = create_temporary(f, &t, tlen);
    if (e) {
        char why[128];
        release_signals(&old);
        errno_text(e, why, sizeof why);
        outfile_release(f);
        return out_fail(TG_ERR_RUNTIME, msg, msgsize, why, NULL);
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
    char dir[PATH_MAX];
    int fd;
    dir_of(path, dir);
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
        tgp_say(msg, msgsize, "cannot write: file not open");
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
        tgp_say(msg, msgsize, "cannot write: %s", strerror(err));
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
        tgp_say(msg, msgsize, "cannot write: out of memory");
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
