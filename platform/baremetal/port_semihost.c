/* SPDX-License-Identifier: MIT */
/*
 * port_semihost.c - port.h straight over semihosting, for a bare-metal
 * target without a C library (the Cortex-M0 build links with -nostdlib).
 */
#include "port.h"
#include "semihost.h"

int port_open(const char *path) { return sh_open_write(path); }
int port_write(int handle, const void *data, size_t n) { return sh_write(handle, data, n); }
int port_close(int handle) { return sh_close(handle) == 0 ? 0 : -1; }
void port_log(const char *line)
{
    sh_write0(line);
    sh_write0("\n");
}
long port_clock_cs(void) { return sh_clock(); }
