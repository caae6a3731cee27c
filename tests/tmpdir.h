/* SPDX-License-Identifier: MIT */
/*
 * tmpdir.h - a scratch directory for the hosted platform's tests
 * (test_image.c, test_file.c): made by tmpdir_make, emptied and removed by
 * tmpdir_remove; tmp_path names a file in it.
 */
#ifndef TG_TMPDIR_H
#define TG_TMPDIR_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char tmpdir[256];

static inline int tmpdir_make(const char *tag)
{
    const char *base = getenv("TMPDIR");
    snprintf(tmpdir, sizeof tmpdir, "%s/tgi_%s_XXXXXX", base && *base ? base : "/tmp", tag);
    if (mkdtemp(tmpdir)) return 0;
    perror("mkdtemp");
    return 1;
}

/* A path in the scratch directory; four calls may be live at once. */
static inline const char *tmp_path(const char *name)
{
    static char buf[4][512];
    static int next;
    char *p = buf[next++ & 3];
    snprintf(p, 512, "%s/%s", tmpdir, name);
    return p;
}

static inline int write_raw(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    size_t w;
    if (!f) return 1;
    w = fwrite(data, 1, n, f);
    return fclose(f) != 0 || w != n;
}

/* Entries of the scratch directory whose name contains `mark`. */
static inline int tmpdir_count(const char *mark)
{
    DIR *d = opendir(tmpdir);
    struct dirent *e;
    int n = 0;
    if (!d) return -1;
    while ((e = readdir(d)) != NULL)
        if (strstr(e->d_name, mark)) n++;
    closedir(d);
    return n;
}

/* Left-over temporaries of the atomic writer (platform/hosted/file.h). */
static inline int count_temporaries(void)
{
    return tmpdir_count(".tinygi-tmp-");
}

static inline void tmpdir_remove(void)
{
    DIR *d = opendir(tmpdir);
    struct dirent *e;
    char p[600];
    if (!d) return;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.' && (!e->d_name[1] || (e->d_name[1] == '.' && !e->d_name[2]))) continue;
        snprintf(p, sizeof p, "%s/%s", tmpdir, e->d_name);
        if (unlink(p) != 0) rmdir(p);
    }
    closedir(d);
    rmdir(tmpdir);
}

#endif
