/* SPDX-License-Identifier: MIT */
/*
 * file.h - the hosted platform's files: read a whole file, hand OBJ meshes
 * to the scene parser (a tg_io), and write files atomically.
 *
 * READING (tgp_file_read)
 *   Only regular files are read: a directory, a FIFO, a device (/dev/zero),
 *   a socket is refused before any byte is read, so a FIFO without a writer
 *   never blocks the program.  A file larger than TG_MAX_FILE_BYTES
 *   (tinygi.h, 1 GiB) is refused by its size before it is read; a file that
 *   grows while it is read, or reports no size (/proc), is read only up to
 *   the limit and then refused.  Memory is allocated for the size the file
 *   has, never for the limit.
 *
 * ATOMIC WRITES (tgp_outfile)
 *   The output goes to a temporary file in the SAME directory as the
 *   destination, ".NAME.tinygi-tmp-PID-N" (NAME cut short so the temporary
 *   name always fits the file system's name limit), created with O_EXCL and
 *   mode 0666 minus the umask and locked (fcntl) while it is written; then
 *   it is fsync'ed, renamed over the destination and the directory is
 *   fsync'ed.  A failed, aborted or interrupted write removes the temporary
 *   and never touches an existing file at the destination; readers see
 *   either the old file or the complete new one.
 *   - A symbolic link at the destination is followed (as cp and compilers
 *     do): the file it names is replaced, the link stays.
 *   - An existing destination keeps its permission bits (not its owner:
 *     the new file belongs to whoever runs the program).
 *   - An existing destination that is read-only (no write permission bit
 *     at all, or not writable by the user) is refused, as the shell's `>`
 *     refuses it: make it writable or remove it first.  So is one that is
 *     not a regular file (a directory, a device, a FIFO).
 *   - Stale temporaries: a process killed with SIGKILL (or a power cut)
 *     leaves its temporary behind.  The first output written into a
 *     directory removes the temporaries there that match the name above,
 *     belong to the same user, name a process that no longer exists, and
 *     are not locked (so a live writer on another machine sharing the
 *     directory keeps its file).
 *
 * ERRORS
 *   Functions returning int give 0 on success and non-zero on failure, with
 *   a one-line reason in `msg` when msg is not NULL: what went wrong, without
 *   the path ("cannot read: no such file or directory"); the caller shows it
 *   as "PATH: error: REASON".  Where it says so, the non-zero value is
 *   TG_ERR_INPUT (the input or the name given is at fault) or TG_ERR_RUNTIME
 *   (out of memory, an I/O error, the file system refuses).
 */
#ifndef TG_HOSTED_FILE_H
#define TG_HOSTED_FILE_H

#include <stddef.h>
#include <sys/types.h>
#include "tinygi.h"

/* Which file a path named when it was read: same device and inode is the
 * same file, whatever links led to it. */
typedef struct tgp_file_id {
    dev_t dev;
    ino_t ino;
} tgp_file_id;

/* Read the whole regular file into a malloc'd buffer with one NUL byte
 * appended (not counted in *size); the caller frees *data.  Returns 0,
 * TG_ERR_INPUT (missing, permission denied, a directory, not a regular file,
 * larger than TG_MAX_FILE_BYTES) or TG_ERR_RUNTIME (out of memory, I/O
 * error).  msg: "cannot read: REASON". */
int tgp_file_read(const char *path, char **data, size_t *size, char *msg, size_t msgsize);
/* The same with any limit in bytes, the short REASON alone in msg
 * ("permission denied", "larger than the 1 GiB limit"), and the file's
 * identity in *id when id is not NULL. */
int tgp_file_read_limited(const char *path, size_t limit, char **data, size_t *size,
                          tgp_file_id *id, char *msg, size_t msgsize);
/* printf into msg (msgsize bytes, cut to fit); nothing when msg is NULL:
 * how the hosted platform writes its messages. */
void tgp_say(char *msg, size_t msgsize, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* "1 GiB", "64 KiB" or "1000 bytes": a byte count as the limits are said. */
void tgp_bytes_text(size_t bytes, char *buf, size_t size);

/* 0 and *id set if path names an existing file (links followed), else 1. */
int tgp_file_identify(const char *path, tgp_file_id *id);
/* 1 if path names an existing file that is `id`. */
int tgp_file_is(const char *path, const tgp_file_id *id);

/* ---- a tg_io for the scene parser: reads the paths it is given ---- */
typedef struct tgp_host_io_file {
    struct tgp_host_io_file *next;
    char *data;
    tgp_file_id id;
    char *path;               /* as the parser asked for it */
} tgp_host_io_file;

typedef struct tgp_host_io {
    tg_io io;                /* pass &host.io to tg_scene_parse */
    tgp_host_io_file *files;  /* every file read, newest first; freed by tgp_host_io_free */
    char last_error[256];    /* why the last read failed, a short phrase ("" if none) */
    int last_status;         /* TG_ERR_INPUT or TG_ERR_RUNTIME for it, 0 if none */
} tgp_host_io;

void tgp_host_io_init(tgp_host_io *h);
/* Free every file read so far (call after tg_scene_parse returns) and
 * forget the last error. */
void tgp_host_io_free(tgp_host_io *h);

/* ---- atomic output ---- */
typedef struct tgp_outfile {
    int fd;                  /* -1 when not open */
    char *path, *tmp_path;   /* path: the file replaced (symbolic links followed) */
    unsigned char buf[65536];
    size_t buffered;
    int failed;              /* errno of the first failed write, 0 if none */
} tgp_outfile;

/* Checks before a long job that `path` can be written as above: returns 0,
 * TG_ERR_INPUT when the name itself cannot be used (empty, ends in '/', a
 * component longer than the file system allows, a path longer than
 * PATH_MAX) or TG_ERR_RUNTIME when the file system refuses (missing or
 * unwritable directory, a read-only file, a directory or another
 * non-regular file in the way, a loop of symbolic links). */
int tgp_outfile_check(const char *path, char *msg, size_t msgsize);

int tgp_outfile_open(tgp_outfile *f, const char *path, char *msg, size_t msgsize);
/* Buffered write; errors are remembered and reported by tgp_outfile_commit. */
void tgp_outfile_write(tgp_outfile *f, const void *data, size_t n);
/* Flush, fsync, rename over the destination.  On failure the temporary
 * file is removed and the destination is left as it was. */
int tgp_outfile_commit(tgp_outfile *f, char *msg, size_t msgsize);
/* Give up: remove the temporary file; the destination is untouched. */
void tgp_outfile_abort(tgp_outfile *f);

/* Install SIGINT/SIGTERM/SIGHUP/SIGPIPE handlers that remove the temporary
 * file being written (if any) and then die of the signal as usual.  A
 * signal the process inherited as ignored (nohup, `cmd &` in a script)
 * stays ignored. */
void tgp_outfile_remove_on_signals(void);

/* Remove the stale temporaries in directory `dir` (see above); returns how
 * many.  tgp_outfile_open does this once per directory. */
int tgp_outfile_remove_stale(const char *dir);

/* The outfile on the heap (it holds a 64 KiB buffer): allocated and opened,
 * or NULL with the reason in msg. */
tgp_outfile *tgp_outfile_create(const char *path, char *msg, size_t msgsize);
/* tgp_outfile_commit, then free the outfile; 0 on success. */
int tgp_outfile_finish(tgp_outfile *f, char *msg, size_t msgsize);

/* Whole buffer to `path`, atomically. */
int tgp_file_write_atomic(const char *path, const void *data, size_t size,
                         char *msg, size_t msgsize);

#endif
