/* SPDX-License-Identifier: MIT */
/*
 * port_stdio.c - port.h over C stdio: used on Linux (x86-64, i686, s390x,
 * powerpc) and on Cortex-M with newlib, whose librdimon turns fopen/fwrite
 * into semihosting calls.
 */
#include "port.h"

#include <stdio.h>
#include <time.h>

#define PORT_MAX_FILES 4
static FILE *port_files[PORT_MAX_FILES];

int port_open(const char *path)
{
    int h;
    for (h = 0; h < PORT_MAX_FILES; h++) {
        if (!port_files[h]) {
            port_files[h] = fopen(path, "wb");
            return port_files[h] ? h : -1;
        }
    }
    return -1;
}

int port_write(int handle, const void *data, size_t n)
{
    if (handle < 0 || handle >= PORT_MAX_FILES || !port_files[handle]) return -1;
    return fwrite(data, 1, n, port_files[handle]) == n ? 0 : -1;
}

int port_close(int handle)
{
    int bad;
    if (handle < 0 || handle >= PORT_MAX_FILES || !port_files[handle]) return -1;
    bad = ferror(port_files[handle]);
    bad |= fclose(port_files[handle]);
    port_files[handle] = 0;
    return bad ? -1 : 0;
}

void port_log(const char *line)
{
    fputs(line, stdout);
    fputc('\n', stdout);
    fflush(stdout);
}

long port_clock_cs(void) { return (long)(clock() / (CLOCKS_PER_SEC / 100)); }
