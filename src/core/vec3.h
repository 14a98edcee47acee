/* vec3.h - 3-vectors and 3x3 matrices as plain values (static inline, no allocation). */
#ifndef LV_CORE_VEC3_H
#define LV_CORE_VEC3_H

#include <math.h>

typedef struct lv_vec3 {
    double x, y, z;
} lv_vec3;

/* Row-major 3x3 matrix: m[row][col]. A rotation C_a_b maps b-frame components to a-frame. */
typedef struct lv_mat3 {
    double m[3][3];
} lv_mat3;

static inline lv_vec3 lv_v3(double x, double y, double z) { return (lv_vec3){x, y, z}; }
static inline lv_vec3 lv_v3_add(lv_vec3 a, lv_vec3 b) { return (lv_vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline lv_vec3 lv_v3_sub(lv_vec3 a, lv_vec3 b) { return (lv_vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline lv_vec3 lv_v3_scale(lv_vec3 a, double s) { return (lv_vec3){a.x * s, a.y * s, a.z * s}; }
static inline double lv_v3_dot(lv_vec3 a, lv_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline lv_vec3 lv_v3_cross(lv_vec3 a, lv_vec3 b)
{
    return (lv_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static inline double lv_v3_norm(lv_vec3 a) { return sqrt(lv_v3_dot(a, a)); }
static inline lv_vec3 lv_v3_unit(lv_vec3 a) { return lv_v3_scale(a, 1.0 / lv_v3_norm(a)); }

static inline lv_vec3 lv_m3_mul_v3(const lv_mat3 *C, lv_vec3 v)
{
    return (lv_vec3){C->m[0][0] * v.x + C->m[0][1] * v.y + C->m[0][2] * v.z,
                     C->m[1][0] * v.x + C->m[1][1] * v.y + C->m[1][2] * v.z,
                     C->m[2][0] * v.x + C->m[2][1] * v.y + C->m[2][2] * v.z};
}
/* Transpose times vector: for a rotation, the inverse mapping. */
static inline lv_vec3 lv_m3t_mul_v3(const lv_mat3 *C, lv_vec3 v)
{
    return (lv_vec3){C->m[0][0] * v.x + C->m[1][0] * v.y + C->m[2][0] * v.z,
                     C->m[0][1] * v.x + C->m[1][1] * v.y + C->m[2][1] * v.z,
                     C->m[0][2] * v.x + C->m[1][2] * v.y + C->m[2][2] * v.z};
}
static inline lv_mat3 lv_m3_mul(const lv_mat3 *A, const lv_mat3 *B)
{
    lv_mat3 R;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            R.m[i][j] = A->m[i][0] * B->m[0][j] + A->m[i][1] * B->m[1][j] + A->m[i][2] * B->m[2][j];
    return R;
}
static inline lv_mat3 lv_m3_transpose(const lv_mat3 *A)
{
    lv_mat3 R;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            R.m[i][j] = A->m[j][i];
    return R;
}

#endif
