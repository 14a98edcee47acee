/* export_glb.c - the vehicle shapes of the CZML export: a stack of stages as a binary glTF 2.0
 * (.glb) built from the stages' geometry, and base64 for the data URI it travels in
 * (docs/exports.md, "Vehicle models"). glTF 2.0 specification (Khronos, 2021): GLB layout
 * section 4.4, accessors 3.6, meshes 3.7 (POSITION needs min/max; COLOR_0 multiplies the base
 * colour), materials 3.9. Axes: the body's x (nose) is glTF +z, its z (down) glTF -y, its y
 * (right) glTF -x, so that CesiumJS, which turns a glTF's +y up to its +z and its +z forward
 * to its +x (ModelUtility.getAxisCorrectionMatrix, forwardAxis Z), holds the model with
 * local +x = body x, +y = -body y, +z = -body z. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"
#include "core/units.h"
#include "post/export_int.h"

#define SEG 20 /* segments around a cylinder or cone */

typedef struct mesh {
    float *v;          /* per vertex: position (3), normal (3), colour (3), glTF axes */
    size_t nv, cap_v;
    uint16_t *ix;
    size_t ni, cap_i;
    int oom;           /* 1: out of memory, or more than 65535 vertices */
} mesh;

/* A vertex given in body axes (x forward, y right, z down): stored in glTF axes. */
static size_t vert(mesh *m, double x, double y, double z, double nx, double ny, double nz,
                   const float col[3])
{
    if (m->nv >= 65535) {
        m->oom = 1;
        return 0;
    }
    if (m->nv == m->cap_v) {
        const size_t cap = m->cap_v ? 2 * m->cap_v : 256;
        float *nvp = realloc(m->v, cap * 9 * sizeof *nvp);
        if (nvp == NULL) {
            m->oom = 1;
            return 0;
        }
        m->v = nvp;
        m->cap_v = cap;
    }
    float *p = m->v + 9 * m->nv;
    const double len = sqrt(nx * nx + ny * ny + nz * nz);
    const double s = len > 0.0 ? 1.0 / len : 0.0;
    p[0] = (float)-y;
    p[1] = (float)-z;
    p[2] = (float)x;
    p[3] = (float)(-ny * s);
    p[4] = (float)(-nz * s);
    p[5] = (float)(nx * s);
    p[6] = col[0];
    p[7] = col[1];
    p[8] = col[2];
    return m->nv++;
}

/* A triangle, wound counter-clockwise seen from the side its vertices' normal points to
 * (glTF's front face, section 3.7.2.1: a double-sided material flips the normal of a back face,
 * so a wrong winding would turn the lit side dark). */
static void tri(mesh *m, size_t a, size_t b, size_t c)
{
    if (m->oom)
        return;
    const float *pa = m->v + 9 * a, *pb = m->v + 9 * b, *pc = m->v + 9 * c;
    const double e1[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
    const double e2[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
    const double g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    if (g[0] * pa[3] + g[1] * pa[4] + g[2] * pa[5] < 0.0) { /* clockwise: swap b and c */
        const size_t t = b;
        b = c;
        c = t;
    }
    if (m->ni + 3 > m->cap_i) {
        const size_t cap = m->cap_i ? 2 * m->cap_i : 768;
        uint16_t *ni = realloc(m->ix, cap * sizeof *ni);
        if (ni == NULL) {
            m->oom = 1;
            return;
        }
        m->ix = ni;
        m->cap_i = cap;
    }
    m->ix[m->ni++] = (uint16_t)a;
    m->ix[m->ni++] = (uint16_t)b;
    m->ix[m->ni++] = (uint16_t)c;
}

/* A disk at x of radius rad facing direction dir (+1 forward, -1 aft). */
static void disk(mesh *m, double x, double rad, double dir, const float col[3])
{
    const size_t c = vert(m, x, 0, 0, dir, 0, 0, col);
    size_t first = 0;
    for (int j = 0; j < SEG; j++) {
        const double a = 2.0 * LV_PI * j / SEG;
        const size_t k = vert(m, x, rad * cos(a), rad * sin(a), dir, 0, 0, col);
        if (j == 0)
            first = k;
    }
    for (int j = 0; j < SEG; j++)
        tri(m, c, first + (size_t)j, first + (size_t)((j + 1) % SEG));
}

/* The mantle of a frustum from x0 (radius r0) to x1 (radius r1 >= 0). */
static void mantle(mesh *m, double x0, double r0, double x1, double r1, const float col[3])
{
    const double slope = (r0 - r1) / (x1 - x0); /* outward normal: (slope, cos, sin) */
    size_t first = 0;
    for (int j = 0; j < SEG; j++) {
        const double a = 2.0 * LV_PI * j / SEG, c = cos(a), s = sin(a);
        const size_t k = vert(m, x0, r0 * c, r0 * s, slope, c, s, col);
        (void)vert(m, x1, r1 * c, r1 * s, slope, c, s, col);
        if (j == 0)
            first = k;
    }
    for (int j = 0; j < SEG; j++) {
        const size_t a0 = first + 2 * (size_t)j, a1 = a0 + 1;
        const size_t b0 = first + 2 * (size_t)((j + 1) % SEG), b1 = b0 + 1;
        tri(m, a0, a1, b1);
        tri(m, a0, b1, b0);
    }
}

/* A flat triangle (double-sided material) with normal n. */
static void plate(mesh *m, const double p[3][3], const double n[3], const float col[3])
{
    size_t k[3];
    for (int i = 0; i < 3; i++)
        k[i] = vert(m, p[i][0], p[i][1], p[i][2], n[0], n[1], n[2], col);
    tri(m, k[0], k[1], k[2]);
}

/* ------------------------------------------------------------------ glb -- */

typedef struct sbuf {
    char *s;
    size_t n, cap;
    int oom;
} sbuf;

static void sb_printf(sbuf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void sb_printf(sbuf *b, const char *fmt, ...)
{
    if (b->oom)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        const int k = vsnprintf(b->s ? b->s + b->n : NULL, b->s ? b->cap - b->n : 0, fmt, ap);
        va_end(ap);
        if (k < 0) {
            b->oom = 1;
            return;
        }
        if (b->s != NULL && b->n + (size_t)k < b->cap) {
            b->n += (size_t)k;
            return;
        }
        const size_t cap = (b->cap ? 2 * b->cap : 2048) + (size_t)k;
        char *ns = realloc(b->s, cap);
        if (ns == NULL) {
            b->oom = 1;
            return;
        }
        b->s = ns;
        b->cap = cap;
    }
}

static void put_u32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v & 0xff);
    p[1] = (unsigned char)((v >> 8) & 0xff);
    p[2] = (unsigned char)((v >> 16) & 0xff);
    p[3] = (unsigned char)((v >> 24) & 0xff);
}

static void put_f32(unsigned char *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put_u32(p, u);
}

/* The mesh as a .glb: one node, one mesh, one primitive (POSITION, NORMAL, COLOR_0, uint16
 * indices), one double-sided matte material. */
static lv_status to_glb(const mesh *m, unsigned char **out, size_t *out_len, lv_err *err)
{
    const size_t nv = m->nv, vbytes = nv * 12, ibytes = m->ni * 2;
    const size_t ipad = (ibytes + 3) / 4 * 4;
    const size_t bin = 3 * vbytes + ipad; /* positions, normals, colours, indices */
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < nv; i++)
        for (int c = 0; c < 3; c++) {
            lo[c] = fminf(lo[c], m->v[9 * i + (size_t)c]);
            hi[c] = fmaxf(hi[c], m->v[9 * i + (size_t)c]);
        }
    sbuf j = {0};
    sb_printf(&j, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"lvsim export\"},"
              "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
              "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
              "\"COLOR_0\":2},\"indices\":3,\"material\":0,\"mode\":4}]}],"
              "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,1],"
              "\"metallicFactor\":0,\"roughnessFactor\":0.7},\"doubleSided\":true}],"
              "\"buffers\":[{\"byteLength\":%zu}],\"bufferViews\":["
              "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu,\"target\":34962},"
              "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962},"
              "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962},"
              "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34963}],",
              bin, vbytes, vbytes, vbytes, 2 * vbytes, vbytes, 3 * vbytes, ibytes);
    sb_printf(&j, "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,"
              "\"type\":\"VEC3\",\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]},"
              "{\"bufferView\":1,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
              "{\"bufferView\":2,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
              "{\"bufferView\":3,\"componentType\":5123,\"count\":%zu,\"type\":\"SCALAR\"}]}",
              nv, (double)lo[0], (double)lo[1], (double)lo[2], (double)hi[0], (double)hi[1],
              (double)hi[2], nv, nv, m->ni);
    if (j.oom) {
        free(j.s);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    const size_t jpad = (j.n + 3) / 4 * 4;
    const size_t total = 12 + 8 + jpad + 8 + bin;
    unsigned char *g = malloc(total);
    if (g == NULL) {
        free(j.s);
        return lv_fail(err, LV_ERR_NOMEM, "out of memory");
    }
    memcpy(g, "glTF", 4);
    put_u32(g + 4, 2);
    put_u32(g + 8, (uint32_t)total);
    put_u32(g + 12, (uint32_t)jpad);
    memcpy(g + 16, "JSON", 4);
    memcpy(g + 20, j.s, j.n);
    memset(g + 20 + j.n, ' ', jpad - j.n); /* the JSON chunk is padded with spaces */
    free(j.s);
    unsigned char *b = g + 20 + jpad;
    put_u32(b, (uint32_t)bin);
    memcpy(b + 4, "BIN\0", 4);
    b += 8;
    for (int part = 0; part < 3; part++)
        for (size_t i = 0; i < nv; i++)
            for (int c = 0; c < 3; c++, b += 4)
                put_f32(b, m->v[9 * i + 3 * (size_t)part + (size_t)c]);
    for (size_t i = 0; i < m->ni; i++, b += 2) {
        b[0] = (unsigned char)(m->ix[i] & 0xff);
        b[1] = (unsigned char)(m->ix[i] >> 8);
    }
    memset(b, 0, ipad - ibytes);
    *out = g;
    *out_len = total;
    return LV_OK;
}

lv_status lv_ex_glb_stack(const lv_ex_shape *st, size_t n, const int rgb[3], unsigned char **glb,
                          size_t *len, lv_err *err)
{
    *glb = NULL;
    *len = 0;
    mesh m;
    memset(&m, 0, sizeof m);
    const float accent[3] = {(float)rgb[0] / 255.0f, (float)rgb[1] / 255.0f,
                             (float)rgb[2] / 255.0f};
    const float grey[2][3] = {{0.92f, 0.92f, 0.90f}, {0.62f, 0.63f, 0.66f}};
    double total = 0.0;
    for (size_t i = 0; i < n; i++)
        total += st[i].length;
    double x = -0.5 * total; /* the origin (the track's point) at the middle of the stack */
    for (size_t i = 0; i < n; i++) {
        const double len_i = st[i].length, rad = 0.5 * st[i].diameter;
        const float *col = grey[i % 2];
        const int top = i + 1 == n;
        const double cone = top ? fmin(2.0 * st[i].diameter, 0.5 * len_i) : 0.0;
        const double x1 = x + len_i - cone;
        disk(&m, x, rad, -1.0, col);
        mantle(&m, x, rad, x1, rad, col);
        if (top) {
            mantle(&m, x1, rad, x + len_i, 0.0, accent); /* the nose cone: the phase colour */
        } else {
            disk(&m, x1, rad, 1.0, col);
        }
        if (st[i].span > 0.0) { /* a delta wing in the body x-y plane and a fin on top */
            const double hs = 0.5 * st[i].span, chord = 0.6 * len_i;
            const double w[3][3] = {{x, -hs, 0.0}, {x, hs, 0.0}, {x + chord, 0.0, 0.0}};
            const double up[3] = {0.0, 0.0, -1.0};
            plate(&m, w, up, accent);
            const double f[3][3] = {{x, 0.0, -rad}, {x + 0.3 * len_i, 0.0, -rad},
                                    {x, 0.0, -rad - 0.35 * hs}};
            const double side[3] = {0.0, 1.0, 0.0};
            plate(&m, f, side, accent);
        }
        x += len_i;
    }
    lv_status s = m.oom ? lv_fail(err, LV_ERR_NOMEM, "vehicle model: out of memory or more "
                                  "than 65535 vertices")
                        : to_glb(&m, glb, len, err);
    free(m.v);
    free(m.ix);
    return s;
}

char *lv_ex_base64(const unsigned char *p, size_t n)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *out = malloc((n + 2) / 3 * 4 + 1);
    if (out == NULL)
        return NULL;
    char *o = out;
    size_t i = 0;
    for (; i + 2 < n; i += 3) {
        const uint32_t v = (uint32_t)p[i] << 16 | (uint32_t)p[i + 1] << 8 | p[i + 2];
        *o++ = tab[v >> 18];
        *o++ = tab[(v >> 12) & 63];
        *o++ = tab[(v >> 6) & 63];
        *o++ = tab[v & 63];
    }
    if (i < n) { /* RFC 4648 section 4: one or two bytes left, '=' padding */
        const uint32_t v = (uint32_t)p[i] << 16 | (i + 1 < n ? (uint32_t)p[i + 1] << 8 : 0);
        *o++ = tab[v >> 18];
        *o++ = tab[(v >> 12) & 63];
        *o++ = i + 1 < n ? tab[(v >> 6) & 63] : '=';
        *o++ = '=';
    }
    *o = '\0';
    return out;
}
