/* SPDX-License-Identifier: MIT */
/*
 * test_file.c - the hosted platform's files (platform/hosted/file.h):
 * reading only regular files, within the size limit and without reserving
 * memory for it, with a short reason on failure (also through the tg_io the
 * parser uses); atomic writes that replace a whole file or nothing, write
 * through symbolic links, keep an existing file's mode, refuse read-only and
 * non-regular destinations, check names up front and always fit their
 * temporary's name; stale temporaries of dead processes removed, live ones
 * kept; signals inherited as ignored stay ignored.
 */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "check.h"
#include "tmpdir.h"
#include "hosted/file.h"
#include "hosted/image.h"

static int read_text(const char *path, char *buf, size_t size)
{
    char *d;
    size_t n;
    if (tgp_file_read(path, &d, &n, NULL, 0)) return 1;
    snprintf(buf, size, "%s", d);
    free(d);
    return 0;
}

static int mode_of(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (int)(st.st_mode & 07777) : -1;
}

static int is_link(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0 && S_ISLNK(st.st_mode);
}

TEST(atomic_write_replaces_whole_file)
{
    const char *path = tmp_path("atomic.bin");
    char *data;
    size_t n;
    struct stat st;
    mode_t old = umask(022);
    CHECK(write_raw(path, "old contents", 12) == 0, "setup");
    CHECK(tgp_file_write_atomic(path, "new", 3, NULL, 0) == 0, "write");
    CHECK(tgp_file_read(path, &data, &n, NULL, 0) == 0 && n == 3 && memcmp(data, "new", 3) == 0,
          "replaced whole");
    free(data);
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0644, "mode %o (0666 minus umask 022)",
          (unsigned)(st.st_mode & 0777));
    CHECK(count_temporaries() == 0, "no temporaries left");
    umask(old);
}

TEST(atomic_write_abort_leaves_existing_file)
{
    const char *path = tmp_path("keep.ppm");
    tgp_outfile *f = (tgp_outfile *)malloc(sizeof *f);
    char *data;
    size_t n;
    CHECK(write_raw(path, "precious", 8) == 0, "setup");
    CHECK(tgp_outfile_open(f, path, NULL, 0) == 0, "open");
    tgp_ppm_write_header(f, 100, 100);
    tgp_outfile_write(f, "partial", 7);
    CHECK(count_temporaries() == 1, "one temporary while writing");
    tgp_outfile_abort(f);
    CHECK(tgp_file_read(path, &data, &n, NULL, 0) == 0 && n == 8 && memcmp(data, "precious", 8) == 0,
          "existing file untouched");
    free(data);
    CHECK(count_temporaries() == 0, "temporary removed");
    free(f);
}

TEST(atomic_write_failure_leaves_nothing)
{
    char msg[256] = "";
    const char *dirpath = tmp_path("adir");
    const char *missing = tmp_path("no/such/dir/x.ppm");
    uint8_t rgb[3] = { 1, 2, 3 };
    struct stat st;
    /* destination is a directory: rename fails, the directory stays, no temporary */
    CHECK(mkdir(dirpath, 0755) == 0, "setup");
    CHECK(tgp_ppm_write(dirpath, 1, 1, rgb, msg, sizeof msg) != 0, "write over a directory refused");
    CHECK(strstr(msg, "cannot write") != NULL, "message '%s'", msg);
    CHECK(stat(dirpath, &st) == 0 && S_ISDIR(st.st_mode), "directory untouched");
    CHECK(count_temporaries() == 0, "temporary removed");
    CHECK(tgp_outfile_check(dirpath, msg, sizeof msg) == TG_ERR_RUNTIME &&
          strstr(msg, "it is a directory"), "check says no: %s", msg);
    rmdir(dirpath);
    /* missing directory */
    CHECK(tgp_ppm_write(missing, 1, 1, rgb, msg, sizeof msg) != 0, "missing dir refused");
    CHECK(stat(missing, &st) != 0, "nothing created");
    CHECK(tgp_outfile_check(missing, msg, sizeof msg) == TG_ERR_RUNTIME &&
          strstr(msg, "no such file or directory"), "check says no: %s", msg);
    CHECK(tgp_outfile_check(tmp_path("fine.ppm"), msg, sizeof msg) == 0, "%s", msg);
    CHECK(tgp_outfile_check("", msg, sizeof msg) == TG_ERR_INPUT, "empty name");
    CHECK(tgp_outfile_check(tmp_path("sub/"), msg, sizeof msg) == TG_ERR_INPUT &&
          strstr(msg, "not a file name"), "trailing slash: %s", msg);
    /* a size outside the limits is refused before any file is made */
    CHECK(tgp_ppm_write(tmp_path("zero.ppm"), 0, 5, rgb, msg, sizeof msg) != 0, "0x5 refused");
    CHECK(stat(tmp_path("zero.ppm"), &st) != 0, "nothing created");
}

TEST(write_error_midway_leaves_existing_file)
{
    /* A file-size limit makes write() fail part way (EFBIG), even as root. */
    static char big[200000];
    const char *path = tmp_path("full.ppm");
    struct rlimit old, lim;
    char msg[256] = "", *data;
    size_t n;
    CHECK(write_raw(path, "precious", 8) == 0, "setup");
    CHECK(getrlimit(RLIMIT_FSIZE, &old) == 0, "getrlimit");
    lim = old;
    lim.rlim_cur = 1000;
    signal(SIGXFSZ, SIG_IGN);
    CHECK(setrlimit(RLIMIT_FSIZE, &lim) == 0, "setrlimit");
    CHECK(tgp_file_write_atomic(path, big, sizeof big, msg, sizeof msg) != 0, "write past the limit fails");
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, SIG_DFL);
    CHECK(strstr(msg, "cannot write") != NULL, "message '%s'", msg);
    CHECK(tgp_file_read(path, &data, &n, NULL, 0) == 0 && n == 8 && memcmp(data, "precious", 8) == 0,
          "existing file untouched");
    free(data);
    CHECK(count_temporaries() == 0, "no partial temporary left");
}

TEST(file_read_errors)
{
    char *data;
    size_t n;
    char msg[256];
    CHECK(tgp_file_read(tmp_path("nope"), &data, &n, msg, sizeof msg) == TG_ERR_INPUT &&
          !strcmp(msg, "cannot read: no such file or directory"), "%s", msg);
    CHECK(tgp_file_read(tmpdir, &data, &n, msg, sizeof msg) == TG_ERR_INPUT &&
          !strcmp(msg, "cannot read: is a directory"), "%s", msg);
    CHECK(write_raw(tmp_path("empty"), "", 0) == 0, "setup");
    CHECK(tgp_file_read(tmp_path("empty"), &data, &n, msg, sizeof msg) == 0 && n == 0 && data[0] == 0,
          "empty file reads as empty, NUL-terminated");
    free(data);
}

TEST(host_io_reads_and_frees)
{
    tgp_host_io h;
    const char *d1, *d2, *why = NULL;
    size_t n1, n2;
    CHECK(write_raw(tmp_path("m.obj"), "v 0 0 0\n", 8) == 0, "setup");
    tgp_host_io_init(&h);
    CHECK(h.io.read_file(h.io.user, tmp_path("m.obj"), &d1, &n1, &why) == 0 && n1 == 8, "read");
    CHECK(h.io.read_file(h.io.user, tmp_path("m.obj"), &d2, &n2, &why) == 0 && d1 != d2, "second buffer");
    CHECK(memcmp(d1, "v 0 0 0\n", 8) == 0, "both buffers stay valid");
    CHECK(h.files && !strcmp(h.files->path, tmp_path("m.obj")) && tgp_file_is(tmp_path("m.obj"), &h.files->id),
          "the file's path and identity are kept");
    CHECK(h.last_status == 0 && why == NULL, "no reason on success");
    CHECK(h.io.read_file(h.io.user, tmp_path("none.obj"), &d2, &n2, &why) != 0, "missing");
    CHECK(why && !strcmp(why, "no such file or directory"), "reason '%s'", why ? why : "(null)");
    CHECK(h.last_status == TG_ERR_INPUT, "bad input");
    CHECK(h.io.read_file(h.io.user, tmpdir, &d2, &n2, &why) != 0 && why && !strcmp(why, "is a directory"),
          "reason '%s'", why ? why : "(null)");
    tgp_host_io_free(&h);
    CHECK(h.files == NULL && h.last_status == 0 && !h.last_error[0], "freed");
}

/* ---- reading: regular files within the limit ---- */

static void on_alarm(int sig) { (void)sig; }

TEST(read_refuses_non_regular_files)
{
    struct sigaction sa, old;
    char *data = NULL, msg[256] = "";
    size_t n;
    /* a FIFO with no writer: refused at once (before: open() blocked forever;
     * the alarm turns a hang into a failure) */
    CHECK(mkfifo(tmp_path("fifo"), 0644) == 0, "mkfifo");
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_alarm; /* no SA_RESTART: a blocked open() returns EINTR */
    sigaction(SIGALRM, &sa, &old);
    alarm(10);
    CHECK(tgp_file_read(tmp_path("fifo"), &data, &n, msg, sizeof msg) == TG_ERR_INPUT &&
          !strcmp(msg, "cannot read: not a regular file"), "FIFO: %s", msg);
    alarm(0);
    sigaction(SIGALRM, &old, NULL);
    CHECK(data == NULL, "nothing handed out");
    if (access("/dev/zero", R_OK) == 0)
        CHECK(tgp_file_read("/dev/zero", &data, &n, msg, sizeof msg) == TG_ERR_INPUT &&
              !strcmp(msg, "cannot read: not a regular file"), "/dev/zero: %s", msg);
}

TEST(read_refuses_by_size_before_reading)
{
    /* a sparse file one byte over 1 GiB: refused by its size, no memory taken
     * (before: read whole into ~1 GiB of memory, then refused) */
    struct rusage before, after;
    char *data = NULL, msg[256] = "";
    size_t n;
    int fd = open(tmp_path("sparse"), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    CHECK(fd >= 0 && ftruncate(fd, (off_t)TG_MAX_FILE_BYTES + 1) == 0, "sparse file");
    if (fd >= 0) close(fd);
    getrusage(RUSAGE_SELF, &before);
    CHECK(tgp_file_read(tmp_path("sparse"), &data, &n, msg, sizeof msg) == TG_ERR_INPUT &&
          !strcmp(msg, "cannot read: larger than the 1 GiB limit"), "%s", msg);
    getrusage(RUSAGE_SELF, &after);
    CHECK(after.ru_maxrss - before.ru_maxrss < 64 * 1024, "peak memory grew by %ld KiB",
          (long)(after.ru_maxrss - before.ru_maxrss));
    unlink(tmp_path("sparse"));
    /* at and one past a small limit */
    CHECK(write_raw(tmp_path("hundred"), "0123456789012345678901234567890123456789012345678901234567890"
                    "123456789012345678901234567890123456789", 100) == 0, "setup");
    CHECK(tgp_file_read_limited(tmp_path("hundred"), 100, &data, &n, NULL, msg, sizeof msg) == 0 &&
          n == 100 && data[100] == '\0', "100 bytes at a limit of 100: %s", msg);
    free(data);
    CHECK(tgp_file_read_limited(tmp_path("hundred"), 99, &data, &n, NULL, msg, sizeof msg) ==
          TG_ERR_INPUT && !strcmp(msg, "larger than the 99 bytes limit"), "%s", msg);
}

TEST(read_stops_at_the_limit_without_a_size)
{
    /* /proc files say size 0 and have more: reading stops at the limit */
    struct stat st;
    char *data = NULL, msg[256] = "";
    size_t n;
    if (stat("/proc/self/status", &st) != 0 || st.st_size != 0) return; /* no such file here */
    CHECK(tgp_file_read_limited("/proc/self/status", 64, &data, &n, NULL, msg, sizeof msg) ==
          TG_ERR_INPUT && !strcmp(msg, "larger than the 64 bytes limit"), "%s", msg);
    CHECK(tgp_file_read_limited("/proc/self/status", 1 << 20, &data, &n, NULL, msg, sizeof msg) == 0 &&
          n > 64 && strlen(data) == n, "whole: %s", msg);
    free(data);
}

TEST(bytes_as_the_limits_say_them)
{
    char t[64];
    tgp_bytes_text((size_t)1 << 30, t, sizeof t);
    CHECK(!strcmp(t, "1 GiB"), "%s", t);
    tgp_bytes_text((size_t)3 << 20, t, sizeof t);
    CHECK(!strcmp(t, "3 MiB"), "%s", t);
    tgp_bytes_text(65536, t, sizeof t);
    CHECK(!strcmp(t, "64 KiB"), "%s", t);
    tgp_bytes_text(1000, t, sizeof t);
    CHECK(!strcmp(t, "1000 bytes"), "%s", t);
}

/* ---- writing: links, modes, read-only files, names ---- */

TEST(write_goes_through_symbolic_links)
{
    char text[64] = "";
    CHECK(write_raw(tmp_path("target.txt"), "old", 3) == 0, "setup");
    CHECK(symlink("target.txt", tmp_path("link.txt")) == 0, "relative link");
    CHECK(symlink(tmp_path("link.txt"), tmp_path("link2.txt")) == 0, "absolute link to the link");
    CHECK(tgp_file_write_atomic(tmp_path("link2.txt"), "new", 3, NULL, 0) == 0, "write");
    CHECK(is_link(tmp_path("link.txt")) && is_link(tmp_path("link2.txt")), "both links stay links");
    CHECK(read_text(tmp_path("target.txt"), text, sizeof text) == 0 && !strcmp(text, "new"),
          "the target got it: '%s'", text);
    /* relative to the link's own directory, not the current one */
    CHECK(mkdir(tmp_path("sub"), 0755) == 0 && symlink("../target.txt", tmp_path("sub/up.txt")) == 0, "setup");
    CHECK(tgp_file_write_atomic(tmp_path("sub/up.txt"), "up", 2, NULL, 0) == 0, "write");
    CHECK(read_text(tmp_path("target.txt"), text, sizeof text) == 0 && !strcmp(text, "up") &&
          is_link(tmp_path("sub/up.txt")), "'%s'", text);
    /* a dangling link: the file it names is created */
    CHECK(symlink("born.txt", tmp_path("dangling.txt")) == 0, "setup");
    CHECK(tgp_file_write_atomic(tmp_path("dangling.txt"), "born", 4, NULL, 0) == 0, "write");
    CHECK(read_text(tmp_path("born.txt"), text, sizeof text) == 0 && !strcmp(text, "born") &&
          is_link(tmp_path("dangling.txt")), "'%s'", text);
    CHECK(count_temporaries() == 0, "no temporaries");
}

TEST(write_refuses_a_loop_of_links)
{
    char msg[256] = "";
    CHECK(symlink("loop_b", tmp_path("loop_a")) == 0 && symlink("loop_a", tmp_path("loop_b")) == 0, "setup");
    CHECK(tgp_outfile_check(tmp_path("loop_a"), msg, sizeof msg) == TG_ERR_RUNTIME &&
          strstr(msg, "symbolic links"), "%s", msg);
    CHECK(tgp_file_write_atomic(tmp_path("loop_a"), "x", 1, msg, sizeof msg) != 0 &&
          is_link(tmp_path("loop_a")), "refused, the link stays: %s", msg);
}

TEST(write_keeps_the_existing_mode)
{
    mode_t old = umask(022);
    CHECK(write_raw(tmp_path("private.ppm"), "secret", 6) == 0 && chmod(tmp_path("private.ppm"), 0600) == 0,
          "setup");
    CHECK(tgp_file_write_atomic(tmp_path("private.ppm"), "new", 3, NULL, 0) == 0, "write");
    CHECK(mode_of(tmp_path("private.ppm")) == 0600, "0600 kept (before: 0644): %o",
          (unsigned)mode_of(tmp_path("private.ppm")));
    CHECK(chmod(tmp_path("private.ppm"), 0664) == 0, "setup");
    CHECK(tgp_file_write_atomic(tmp_path("private.ppm"), "newer", 5, NULL, 0) == 0, "write");
    CHECK(mode_of(tmp_path("private.ppm")) == 0664, "0664 kept: %o", (unsigned)mode_of(tmp_path("private.ppm")));
    CHECK(tgp_file_write_atomic(tmp_path("fresh.ppm"), "x", 1, NULL, 0) == 0, "write");
    CHECK(mode_of(tmp_path("fresh.ppm")) == 0644, "a new file: 0666 minus umask 022: %o",
          (unsigned)mode_of(tmp_path("fresh.ppm")));
    umask(old);
}

TEST(write_refuses_read_only_and_non_regular_files)
{
    char msg[256] = "", text[64] = "";
    CHECK(write_raw(tmp_path("ro.ppm"), "keep", 4) == 0 && chmod(tmp_path("ro.ppm"), 0444) == 0, "setup");
    CHECK(tgp_outfile_check(tmp_path("ro.ppm"), msg, sizeof msg) == TG_ERR_RUNTIME &&
          strstr(msg, "read-only"), "check: %s", msg);
    CHECK(tgp_file_write_atomic(tmp_path("ro.ppm"), "lost", 4, msg, sizeof msg) != 0 &&
          strstr(msg, "read-only"), "write: %s", msg);
    CHECK(read_text(tmp_path("ro.ppm"), text, sizeof text) == 0 && !strcmp(text, "keep") &&
          mode_of(tmp_path("ro.ppm")) == 0444, "untouched: '%s'", text);
    CHECK(mkfifo(tmp_path("out.fifo"), 0644) == 0, "setup");
    CHECK(tgp_outfile_check(tmp_path("out.fifo"), msg, sizeof msg) == TG_ERR_RUNTIME &&
          strstr(msg, "not a regular file"), "FIFO: %s", msg);
    CHECK(tgp_file_write_atomic(tmp_path("out.fifo"), "x", 1, msg, sizeof msg) != 0, "refused");
    CHECK(count_temporaries() == 0, "no temporaries");
}

/* A name of `len` bytes: `unit` repeated, then 'a's up to len. */
static void make_name(char *name, size_t len, const char *unit)
{
    size_t k = 0, u = strlen(unit);
    while (k + u <= len) memcpy(name + k, unit, u), k += u;
    while (k < len) name[k++] = 'a';
    name[len] = '\0';
}

TEST(long_names_fit_or_are_refused_up_front)
{
    char name[300], msg[256] = "";
    long name_max = pathconf(tmpdir, _PC_NAME_MAX);
    tgp_outfile *f;
    if (name_max <= 0 || name_max > 290) name_max = 255;
    /* the longest name the file system takes: written (before: its temporary's
     * name was too long, and the write failed after the work) */
    make_name(name, (size_t)name_max, "x");
    CHECK(tgp_outfile_check(tmp_path(name), msg, sizeof msg) == 0, "%s", msg);
    f = tgp_outfile_create(tmp_path(name), msg, sizeof msg);
    CHECK(f != NULL, "open: %s", msg);
    CHECK(count_temporaries() == 1, "its temporary exists");
    if (f) CHECK(tgp_outfile_finish(f, msg, sizeof msg) == 0, "%s", msg);
    CHECK(access(tmp_path(name), F_OK) == 0 && count_temporaries() == 0, "written");
    unlink(tmp_path(name));
    /* two-byte UTF-8 characters: the temporary's name is not cut inside one */
    make_name(name, (size_t)name_max, "\xc3\xa9");
    CHECK(tgp_file_write_atomic(tmp_path(name), "e", 1, msg, sizeof msg) == 0, "%s", msg);
    unlink(tmp_path(name));
    /* one byte too many: refused by the check, as bad input */
    make_name(name, (size_t)name_max + 1, "x");
    CHECK(tgp_outfile_check(tmp_path(name), msg, sizeof msg) == TG_ERR_INPUT, "%s", msg);
}

TEST(write_inside_a_utf8_name_cut)
{
    /* the temporary of a long UTF-8 name: its kept part ends on a whole character */
    char name[300];
    long name_max = pathconf(tmpdir, _PC_NAME_MAX);
    tgp_outfile *f;
    DIR *d;
    struct dirent *e;
    int whole = 0;
    if (name_max <= 0 || name_max > 290) name_max = 255;
    make_name(name, (size_t)name_max - 1, "\xc3\xa9");
    f = tgp_outfile_create(tmp_path(name), NULL, 0);
    CHECK(f != NULL, "open");
    d = opendir(tmpdir);
    while (d && (e = readdir(d)) != NULL) {
        const char *mark = strstr(e->d_name, ".tinygi-tmp-");
        if (mark) whole = mark > e->d_name && (unsigned char)mark[-1] == 0xa9 &&
                          (mark - e->d_name - 1) % 2 == 0;
    }
    if (d) closedir(d);
    CHECK(whole, "the name's prefix ends after a whole two-byte character");
    if (f) tgp_outfile_abort(f);
    free(f);
}

/* ---- stale temporaries ---- */

/* A child that opens an output in tmpdir, says so on `ready`, then either
 * exits at once without cleaning up (as after SIGKILL) or waits to be killed. */
static pid_t child_writer(const char *name, int wait_for_kill)
{
    int fds[2];
    char c;
    pid_t pid;
    if (pipe(fds) != 0) return -1;
    pid = fork();
    if (pid == 0) {
        tgp_outfile *f = tgp_outfile_create(tmp_path(name), NULL, 0);
        close(fds[0]);
        if (write(fds[1], f ? "y" : "n", 1) != 1) _exit(1);
        if (wait_for_kill) for (;;) pause();
        _exit(0);
    }
    close(fds[1]);
    if (pid < 0 || read(fds[0], &c, 1) != 1 || c != 'y') pid = -1;
    close(fds[0]);
    return pid;
}

TEST(stale_temporaries_of_dead_processes_removed)
{
    pid_t dead = child_writer("dead.ppm", 0), alive = child_writer("alive.ppm", 1);
    tgp_outfile *mine = tgp_outfile_create(tmp_path("mine.ppm"), NULL, 0);
    char name[128];
    int st, fd, sync[2];
    CHECK(dead > 0 && alive > 0 && mine != NULL, "setup");
    if (dead > 0) waitpid(dead, &st, 0);
    CHECK(count_temporaries() == 3, "three temporaries: %d", count_temporaries());
    CHECK(tgp_outfile_remove_stale(tmpdir) == 1, "the dead writer's temporary is removed");
    CHECK(count_temporaries() == 2, "the live one and mine stay");
    if (alive > 0) {
        kill(alive, SIGKILL);
        waitpid(alive, &st, 0);
    }
    CHECK(tgp_outfile_remove_stale(tmpdir) == 1, "killed with SIGKILL: removed");
    CHECK(count_temporaries() == 1, "mine stays");
    if (mine) tgp_outfile_abort(mine);
    free(mine);
    /* a file of the pattern whose dead PID's lock is held by a live process stays */
    snprintf(name, sizeof name, ".x.ppm.tinygi-tmp-%ld-0", (long)dead);
    fd = open(tmp_path(name), O_RDWR | O_CREAT, 0644);
    CHECK(fd >= 0, "setup");
    if (fd >= 0 && pipe(sync) == 0) {
        char c = 'n';
        pid_t holder = fork();
        if (holder == 0) {
            struct flock fl;
            memset(&fl, 0, sizeof fl);
            fl.l_type = F_WRLCK;
            fl.l_whence = SEEK_SET;
            c = fcntl(fd, F_SETLK, &fl) == 0 ? 'y' : 'n';
            if (write(sync[1], &c, 1) != 1 || c != 'y') _exit(1);
            for (;;) pause();
        }
        close(sync[1]);
        CHECK(holder > 0 && read(sync[0], &c, 1) == 1 && c == 'y', "a live process holds the lock");
        close(sync[0]);
        CHECK(tgp_outfile_remove_stale(tmpdir) == 0 && count_temporaries() == 1, "locked: kept");
        kill(holder, SIGKILL);
        waitpid(holder, &st, 0);
        close(fd);
        CHECK(tgp_outfile_remove_stale(tmpdir) == 1 && count_temporaries() == 0, "lock gone: removed");
    }
    /* names that only look alike are never touched */
    CHECK(write_raw(tmp_path(".y.tinygi-tmp-x-0"), "", 0) == 0 &&
          write_raw(tmp_path("y.tinygi-tmp-999999999-0"), "", 0) == 0, "setup");
    CHECK(tgp_outfile_remove_stale(tmpdir) == 0, "not ours");
    unlink(tmp_path(".y.tinygi-tmp-x-0"));
    unlink(tmp_path("y.tinygi-tmp-999999999-0"));
}

/* ---- signals ---- */

TEST(signals_ignored_at_start_stay_ignored)
{
    struct sigaction hup, term, old_hup, old_term;
    memset(&hup, 0, sizeof hup);
    hup.sa_handler = SIG_IGN;
    sigaction(SIGHUP, &hup, &old_hup);  /* as nohup starts a program */
    signal(SIGTERM, SIG_DFL);
    sigaction(SIGTERM, NULL, &old_term);
    tgp_outfile_remove_on_signals();
    sigaction(SIGHUP, NULL, &hup);
    sigaction(SIGTERM, NULL, &term);
    CHECK(hup.sa_handler == SIG_IGN, "SIGHUP still ignored (before: a handler that died of it)");
    CHECK(term.sa_handler != SIG_IGN && term.sa_handler != SIG_DFL, "SIGTERM handled");
    sigaction(SIGHUP, &old_hup, NULL);
    sigaction(SIGTERM, &old_term, NULL);
}

int main(void)
{
    if (tmpdir_make("file")) return 1;
    RUN(atomic_write_replaces_whole_file);
    RUN(atomic_write_abort_leaves_existing_file);
    RUN(atomic_write_failure_leaves_nothing);
    RUN(write_error_midway_leaves_existing_file);
    RUN(file_read_errors);
    RUN(host_io_reads_and_frees);
    RUN(read_refuses_non_regular_files);
    RUN(read_refuses_by_size_before_reading);
    RUN(read_stops_at_the_limit_without_a_size);
    RUN(bytes_as_the_limits_say_them);
    RUN(write_goes_through_symbolic_links);
    RUN(write_refuses_a_loop_of_links);
    RUN(write_keeps_the_existing_mode);
    RUN(write_refuses_read_only_and_non_regular_files);
    RUN(long_names_fit_or_are_refused_up_front);
    RUN(write_inside_a_utf8_name_cut);
    RUN(stale_temporaries_of_dead_processes_removed);
    RUN(signals_ignored_at_start_stay_ignored);
    tmpdir_remove();
    return check_summary();
}
