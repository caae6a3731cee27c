/* SPDX-License-Identifier: MIT */
/*
 * peer_s3l.c - small3dlib (github.com/viteo/small3dlib, drummyfish's
 * single-header rasterizer) drawing the sphere of tools/bench_raster.c: an
 * indexed mesh (the triangle corners merged by position), its full 32-bit
 * z-buffer (S3L_Z_BUFFER 1), affine interpolation (its default), back
 * faces culled; the pixel function interpolates the three vertices'
 * colours (0.5 n + 0.5) with the barycentric coordinates and writes a
 * 32-bit pixel.  small3dlib fixes the resolution when compiled:
 * tools/peers/build.sh builds one program a size (-DPEER_W, -DPEER_H).
 */
#include "peer_common.h"
#include <stdint.h>

#define S3L_RESOLUTION_X PEER_W
#define S3L_RESOLUTION_Y PEER_H
#define S3L_PIXEL_FUNCTION draw_pixel
#define S3L_Z_BUFFER 1
#include <small3dlib.h>   /* the peer's, on the -I path (tools/peers/build.sh) */

static uint32_t frame[PEER_W * PEER_H];
static S3L_Unit *verts;
static S3L_Index *tri_idx;
static uint8_t (*vcol)[3];
static int nverts;
static S3L_Model3D model;
static S3L_Scene scene;

static const char *peer_name(void) { return "small3dlib"; }

static inline void draw_pixel(S3L_PixelInfo *p)
{
    const S3L_Index *t = tri_idx + 3 * p->triangleIndex;
    const uint8_t *a = vcol[t[0]], *b = vcol[t[1]], *c = vcol[t[2]];
    const int32_t u = p->barycentric[0], v = p->barycentric[1], w = p->barycentric[2];   /* sum S3L_F = 2^9 */
    frame[p->y * PEER_W + p->x] = (((uint32_t)(a[0] * u + b[0] * v + c[0] * w) >> 9) & 0xFF)
                                | ((((uint32_t)(a[1] * u + b[1] * v + c[1] * w) >> 9) & 0xFF) << 8)
                                | ((((uint32_t)(a[2] * u + b[2] * v + c[2] * w) >> 9) & 0xFF) << 16);
}

static int find_vertex(const float *v)
{
    int i;
    for (i = nverts - 1; i >= 0 && i >= nverts - 2 * SPHERE_SLICES - 4; i--)   /* the ring above or this one */
        if (verts[3 * i] == (S3L_Unit)lroundf(v[0] * S3L_F) && verts[3 * i + 1] == (S3L_Unit)lroundf(v[1] * S3L_F)
            && verts[3 * i + 2] == (S3L_Unit)lroundf(v[2] * S3L_F) && vcol[i][0] == (uint8_t)lroundf((0.5f * v[0] + 0.5f) * 255)
            && vcol[i][1] == (uint8_t)lroundf((0.5f * v[1] + 0.5f) * 255)
            && vcol[i][2] == (uint8_t)lroundf((0.5f * v[2] + 0.5f) * 255))
            return i;
    return -1;
}

static int peer_setup(int w, int h, const float *pos, int tris)
{
    int i, k;
    if (w != PEER_W || h != PEER_H) return 0;
    verts = (S3L_Unit *)malloc(sizeof(S3L_Unit) * 9 * (size_t)tris);
    tri_idx = (S3L_Index *)malloc(sizeof(S3L_Index) * 3 * (size_t)tris);
    vcol = (uint8_t (*)[3])malloc(3 * 3 * (size_t)tris);
    if (!verts || !tri_idx || !vcol) return 0;
    nverts = 0;
    for (i = 0; i < 3 * tris; i++) {
        const float *v = pos + 3 * i;
        int j = find_vertex(v);
        if (j < 0) {
            j = nverts++;
            for (k = 0; k < 3; k++) {
                verts[3 * j + k] = (S3L_Unit)lroundf(v[k] * S3L_F);
                vcol[j][k] = (uint8_t)lroundf((0.5f * v[k] + 0.5f) * 255);
            }
        }
        if (j > 65535) return 0;   /* S3L_Index is 16 bits */
        tri_idx[i] = (S3L_Index)j;
    }
    S3L_model3DInit(verts, (S3L_Index)nverts, tri_idx, (S3L_Index)tris, &model);
    model.config.backfaceCulling = 1;   /* clockwise culled: the outside, counter-clockwise, shows (the centre pixel faces -z) */
    S3L_sceneInit(&model, 1, &scene);
    scene.camera.transform.translation.z = (S3L_Unit)lround(-SPHERE_CAM_DIST * S3L_F);
    /* the projection plane spans x in [-1, 1] and y in [-h/w, h/w] at the
     * focal length: tan(fov / 2) = (h / w) / focal; times 1.015, as its
     * integer projection drew the sphere 1.5% smaller than the others */
    scene.camera.focalLength = (S3L_Unit)lround((double)h / w / tan(SPHERE_CAM_FOV / 2) * S3L_F * 1.015);
    return 1;
}

static void __attribute__((noinline)) bench_clear(void)
{
    memset(frame, 0, sizeof frame);
    S3L_newFrame();
}

static void __attribute__((noinline)) bench_draw(void)
{
    S3L_drawScene(scene);
}

static long peer_covered(void)
{
    long n = 0;
    int i;
    for (i = 0; i < PEER_W * PEER_H; i++) n += frame[i] != 0;
    return n;
}

/* The centre pixel's blue: the near hemisphere faces -z (blue below 128). */
static void peer_done(void)
{
    if (getenv("PEER_CHECK")) fprintf(stderr, "vertices %d, centre pixel 0x%06x\n", nverts,
                                      (unsigned)frame[PEER_H / 2 * PEER_W + PEER_W / 2]);
    free(verts); free(tri_idx); free(vcol);
}

int main(int argc, char **argv) { return peer_main(argc, argv); }
