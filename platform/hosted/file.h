/* SPDX-License-Identifier: MIT */
/*
 * file.h - the hosted platform's files: read a whole file, hand OBJ meshes
 * to the scene parser (a tg_io), and write files atomically.
 *
 * ATOMIC WRITES
 *   tgp_outfile writes into a temporary file in the SAME directory as the
 *   destination (".NAME.tmp-PID-N", created with O_EXCL and mode 0666 minus
 *   the umask), then fsyncs it, renames it over the destination and fsyncs
 *   the directory.  A failed, aborted or interrupted write removes the
 *   temporary file and never touches an existing file at the destination;
 *   readers see either the old file or the complete new one.
 *
 * ERRORS
 *   Functions returning int give 0 on success and non-zero on failure, with
 *   a one-line reason in `msg` when msg is not NULL: what went wrong, without
 *   the path ("cannot open: No such file or directory"); the caller shows it
 *   as "PATH: error: REASON".
 */
#ifndef TG_HOSTED_FILE_H
#define TG_HOSTED_FILE_H

#include <stddef.h>
#include "tinygi.h"

/* Largest file tgp_file_read accepts (scene text, OBJ, images): 1 GiB. */
#define TG_FILE_MAX_BYTES ((size_t)1 << 30)

/* Read the whole file into a malloc'd buffer with one NUL byte appended
 * (not counted in *size).  The caller frees *data. */
int tgp_file_read(const char *path, char **data, size_t *size, char *msg, size_t msgsize);

/* ---- a tg_io for the scene parser: reads the paths it is given ---- */
typedef struct tgp_host_io_file {
    struct tgp_host_io_file *next;
    char *data;
} tgp_host_io_file;

typedef struct tgp_host_io {
    tg_io io;                /* pass &host.io to tg_scene_parse */
    tgp_host_io_file *files;  /* every buffer handed out, freed by tgp_host_io_free */
    char last_error[256];    /* why the last read failed ("" if none) */
} tgp_host_io;

void tgp_host_io_init(tgp_host_io *h);
/* Free every file read so far (call after tg_scene_parse returns). */
void tgp_host_io_free(tgp_host_io *h);

/* ---- atomic output ---- */
typedef struct tgp_outfile {
    int fd;                  /* -1 when not open */
    char *path, *tmp_path;
    unsigned char buf[65536];
    size_t buffered;
    int failed;              /* errno of the first failed write, 0 if none */
} tgp_outfile;

int tgp_outfile_open(tgp_outfile *f, const char *path, char *msg, size_t msgsize);
/* Buffered write; errors are remembered and reported by tgp_outfile_commit. */
void tgp_outfile_write(tgp_outfile *f, const void *data, size_t n);
/* Flush, fsync, rename over the destination.  On failure the temporary
 * file is removed and the destination is left as it was. */
int tgp_outfile_commit(tgp_outfile *f, char *msg, size_t msgsize);
/* Give up: remove the temporary file; the destination is untouched. */
void tgp_outfile_abort(tgp_outfile *f);

/* Install SIGINT/SIGTERM/SIGHUP/SIGPIPE handlers that remove the temporary
 * file being written (if any) and then die of the signal as usual. */
void tgp_outfile_remove_on_signals(void);

/* The outfile on the heap (it holds a 64 KiB buffer): allocated and opened,
 * or NULL with the reason in msg. */
tgp_outfile *tgp_outfile_create(const char *path, char *msg, size_t msgsize);
/* tgp_outfile_commit, then free the outfile; 0 on success. */
int tgp_outfile_finish(tgp_outfile *f, char *msg, size_t msgsize);

/* Whole buffer to `path`, atomically. */
int tgp_file_write_atomic(const char *path, const void *data, size_t size,
                         char *msg, size_t msgsize);

/* 0 if a file could be created in the directory that holds `path`
 * (checks early, before a long render, that the output can be written). */
int tgp_file_dir_writable(const char *path, char *msg, size_t msgsize);

#endif
