/* SPDX-License-Identifier: MIT */
/* gltf_mesh.c -- the UV sphere a glTF material is shown on, as the bytes of
 * glTF's buffer (little-endian floats and unsigned shorts), and base64. */
#include "export.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static unsigned char *put_u32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v & 0xFF);
    p[1] = (unsigned char)((v >> 8) & 0xFF);
    p[2] = (unsigned char)((v >> 16) & 0xFF);
    p[3] = (unsigned char)((v >> 24) & 0xFF);
    return p + 4;
}

static unsigned char *put_float(unsigned char *p, float x)
{
    uint32_t v;
    memcpy(&v, &x, sizeof v);
    return put_u32(p, v);
}

static unsigned char *put_u16(unsigned char *p, unsigned v)
{
    p[0] = (unsigned char)(v & 0xFF);
    p[1] = (unsigned char)((v >> 8) & 0xFF);
    return p + 2;
}

/* The vertex of ring i (0 at +Y) and segment j: its position, which is also
 * its normal (unit length in double, then rounded to float). */
static void vertex(int i, int j, float pos[3])
{
    const double pi = 3.14159265358979323846;
    double theta = pi * i / GLTF_SEG_LAT, phi = 2 * pi * j / GLTF_SEG_LON;
    double st = i == 0 || i == GLTF_SEG_LAT ? 0 : sin(theta);
    double ct = i == 0 ? 1 : i == GLTF_SEG_LAT ? -1 : cos(theta);
    double v[3] = { st * sin(phi), ct, st * cos(phi) };
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int c = 0; c < 3; c++)
        pos[c] = (float)(v[c] / n);
}

static void write_vertices(gltf_mesh *m)
{
    unsigned char *pp = m->bytes + m->offset[0], *pn = m->bytes + m->offset[1],
                  *pt = m->bytes + m->offset[2];
    for (int c = 0; c < 3; c++) {
        m->min[c] = INFINITY;
        m->max[c] = -INFINITY;
    }
    for (int i = 0; i <= GLTF_SEG_LAT; i++)
        for (int j = 0; j <= GLTF_SEG_LON; j++) {
            float pos[3];
            vertex(i, j, pos);
            for (int c = 0; c < 3; c++) {
                pp = put_float(pp, pos[c]);
                pn = put_float(pn, pos[c]);
                m->min[c] = fminf(m->min[c], pos[c]);
                m->max[c] = fmaxf(m->max[c], pos[c]);
            }
            pt = put_float(pt, (float)j / GLTF_SEG_LON);
            pt = put_float(pt, (float)i / GLTF_SEG_LAT);
        }
}

/* Two triangles a quad, counter-clockwise seen from outside; the one of each
 * quad that would have two corners at a pole is left out. */
static void write_indices(gltf_mesh *m)
{
    unsigned char *p = m->bytes + m->offset[3];
    const int row = GLTF_SEG_LON + 1;
    for (int i = 0; i < GLTF_SEG_LAT; i++)
        for (int j = 0; j < GLTF_SEG_LON; j++) {
            unsigned a = (unsigned)(i * row + j), b = a + (unsigned)row, c = b + 1, d = a + 1;
            if (i != GLTF_SEG_LAT - 1) {
                p = put_u16(p, a);
                p = put_u16(p, b);
                p = put_u16(p, c);
            }
            if (i != 0) {
                p = put_u16(p, a);
                p = put_u16(p, c);
                p = put_u16(p, d);
            }
        }
}

int gltf_mesh_make(gltf_mesh *m)
{
    memset(m, 0, sizeof *m);
    m->length[0] = m->length[1] = (size_t)GLTF_NVERTS * 12;
    m->length[2] = (size_t)GLTF_NVERTS * 8;
    m->length[3] = ((size_t)GLTF_NINDICES * 2 + 3) / 4 * 4; /* 4-byte aligned */
    for (int k = 0; k < 4; k++) {
        m->offset[k] = m->nbytes;
        m->nbytes += m->length[k];
    }
    m->bytes = calloc(m->nbytes, 1);
    if (!m->bytes)
        return -1;
    write_vertices(m);
    write_indices(m);
    return 0;
}

void gltf_mesh_free(gltf_mesh *m)
{
    free(m->bytes);
    m->bytes = NULL;
}

void gltf_base64(FILE *f, const unsigned char *p, size_t n)
{
    static const char digits[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char out[4];
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)p[i] << 16;
        if (i + 1 < n)
            v |= (uint32_t)p[i + 1] << 8;
        if (i + 2 < n)
            v |= p[i + 2];
        out[0] = digits[(v >> 18) & 63];
        out[1] = digits[(v >> 12) & 63];
        out[2] = i + 1 < n ? digits[(v >> 6) & 63] : '=';
        out[3] = i + 2 < n ? digits[v & 63] : '=';
        fwrite(out, 1, 4, f);
    }
}
