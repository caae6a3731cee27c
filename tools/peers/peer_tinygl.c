/* SPDX-License-Identifier: MIT */
/*
 * peer_tinygl.c - TinyGL (github.com/C-Chads/tinygl) drawing the sphere of
 * tools/bench_raster.c: 32-bit RGBA, its 16-bit z-buffer, depth test, back
 * faces culled, smooth shading, lighting off, colour 0.5 n + 0.5 a vertex.
 * Built twice by tools/peers/build.sh: immediate mode (glBegin, glColor3f
 * and glVertex3f a vertex, every frame) and, with -DPEER_LIST=1, the same
 * calls compiled once into a display list replayed by glCallList.
 */
#include "peer_common.h"
#include <GL/gl.h>
#include <zbuffer.h>

#ifndef PEER_LIST
#define PEER_LIST 0
#endif

static ZBuffer *zb;
static const float *g_pos;
static int g_tris, g_w, g_h;
static GLuint list;

static const char *peer_name(void) { return PEER_LIST ? "tinygl-list" : "tinygl"; }

static void sphere_calls(void)
{
    int i;
    glBegin(GL_TRIANGLES);
    for (i = 0; i < 3 * g_tris; i++) {
        const float *p = g_pos + 3 * i;
        glColor3f(0.5f * p[0] + 0.5f, 0.5f * p[1] + 0.5f, 0.5f * p[2] + 0.5f);
        glVertex3f(p[0], p[1], p[2]);
    }
    glEnd();
}

static int peer_setup(int w, int h, const float *pos, int tris)
{
    /* eye space: x_e = -x, y_e = y, z_e = -(z + SPHERE_CAM_DIST) (the camera on
     * -z looking at the origin, y up; a rotation, so windings keep) */
    static const GLfloat view[16] = { -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, (GLfloat)-SPHERE_CAM_DIST, 1 };
    const double top = SPHERE_CAM_NEAR * tan(SPHERE_CAM_FOV / 2), right = top * w / h;
    g_pos = pos; g_tris = tris; g_w = w; g_h = h;
    zb = ZB_open(w, h, ZB_MODE_RGBA, 0);
    if (!zb) return 0;
    glInit(zb);
    glViewport(0, 0, w, h);
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glShadeModel(GL_SMOOTH);
    glDisable(GL_LIGHTING);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-right, right, -top, top, SPHERE_CAM_NEAR, SPHERE_CAM_FAR);
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(view);
    if (PEER_LIST) {
        list = glGenLists(1);
        glNewList(list, GL_COMPILE);
        sphere_calls();
        glEndList();
    }
    return 1;
}

static void __attribute__((noinline)) bench_clear(void)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

static void __attribute__((noinline)) bench_draw(void)
{
    if (PEER_LIST) glCallList(list);
    else sphere_calls();
}

static long peer_covered(void)
{
    long n = 0;
    int x, y;
    for (y = 0; y < g_h; y++) {
        const PIXEL *row = (const PIXEL *)((const char *)zb->pbuf + (size_t)y * zb->linesize);
        for (x = 0; x < g_w; x++) n += (row[x] & 0xFFFFFFu) != 0;   /* cleared black; the sphere never is */
    }
    return n;
}

static void peer_done(void)
{
    if (PEER_LIST) glDeleteLists(list, 1);
    glClose();
    ZB_close(zb);
}

int main(int argc, char **argv) { return peer_main(argc, argv); }
