/* erk.c - Dormand-Prince 5(4) and DOP853 with dense output, PI step-size control, Hairer's
 * stiffness test and state events located on the dense output (see erk.h).
 *
 * Reference: E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential Equations I,
 * Nonstiff Problems, 2nd ed., Springer 1993 ("HNW"):
 *   - DOPRI5: II.5, Table 5.2 (coefficients), its continuous extension of order 4 (II.6,
 *     the dense output of Hairer's code DOPRI5: coefficients d1..d7 below);
 *   - DOP853: II.10 ("DOP853", Dormand & Prince 1980 / Hairer's 8(5,3) code), with its
 *     dense output of order 7 that needs three extra stages per step (II.10, Table 10.x);
 *     coefficients as published with Hairer's code dop853.f (Hairer & Wanner's software page),
 *     cross-checked against the same published table in SciPy's dop853_coefficients.py;
 *   - step-size control: II.4 (4.12)-(4.13) with the PI ("stabilized") controller of Gustafsson
 *     (HNW II, IV.2 / Hairer's codes: fac = err^(1/q - 0.75 beta) / err_old^beta, beta = 0.04);
 *   - initial step: II.4, "Starting Step Size" (Gladwell, Shampine & Brankin's algorithm);
 *   - stiffness detection: IV.2 (2.23)-(2.24) / Hairer's codes: |h lambda| estimated from the
 *     two stages at c = 1, compared with the boundary of the stability domain (3.25 for DOPRI5,
 *     6.1 for DOP853); stiff after 15 positive tests without 6 negative ones in a row.
 * The code is lvsim's own; only the coefficients are taken from the published tables.
 */
#include "integrate/erk.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/status.h"

#define ERK_MAX_STAGES 16 /* DOP853: 12 + the FSAL stage + 3 for the dense output */
#define ERK_MAX_RC 8      /* dense-output coefficient vectors */

/* ---- tableaux ----------------------------------------------------------------- */

/* An explicit embedded pair: stages 0 .. s-1 advance the step (stage s-1 has c = 1: its
 * argument is kept for the stiffness test), y_{n+1} = y_n + h sum_j b_j k_j, and stage s is
 * f(t + h, y_{n+1}) - the next step's first ("first same as last"). Stages s+1 .. s_dense-1
 * serve only the dense output. a is row-major [ERK_MAX_STAGES][ERK_MAX_STAGES]. */
typedef struct rk_tab {
    const char *name;
    int s, s_dense;
    int order;        /* of the propagated solution (initial-step exponent) */
    double expo1;     /* PI controller: 1/(q+1) - 0.75 beta (dopri5) or - 0.2 beta (dop853) */
    double beta;
    double fac_min;   /* largest decrease per step: h_new >= fac_min h (HNW: fac1) */
    double fac_max;   /* largest increase: h_new <= fac_max h (HNW: fac2) */
    double hlamb_max; /* stiffness: |h lambda| beyond this counts as a positive test */
    const double *c, *a, *b;
} rk_tab;

/* Dormand & Prince, HNW I, II.5, Table 5.2 "Dormand-Prince 5(4) (DOPRI5)". */
static const double dp5_c[7] = {0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0};
static const double dp5_a[ERK_MAX_STAGES * ERK_MAX_STAGES] = {
#define A(i, j) [(i)*ERK_MAX_STAGES + (j)]
    A(1, 0) = 1.0 / 5.0,
    A(2, 0) = 3.0 / 40.0, A(2, 1) = 9.0 / 40.0,
    A(3, 0) = 44.0 / 45.0, A(3, 1) = -56.0 / 15.0, A(3, 2) = 32.0 / 9.0,
    A(4, 0) = 19372.0 / 6561.0, A(4, 1) = -25360.0 / 2187.0, A(4, 2) = 64448.0 / 6561.0,
    A(4, 3) = -212.0 / 729.0,
    A(5, 0) = 9017.0 / 3168.0, A(5, 1) = -355.0 / 33.0, A(5, 2) = 46732.0 / 5247.0,
    A(5, 3) = 49.0 / 176.0, A(5, 4) = -5103.0 / 18656.0,
};
static const double dp5_b[6] = {35.0 / 384.0,     0.0,           500.0 / 1113.0,
                                125.0 / 192.0,    -2187.0 / 6784.0, 11.0 / 84.0};
/* b - b^ (the 4th-order embedded weights), Table 5.2: the local error estimate over stages
 * 0..6 (stage 6 is the FSAL stage f(t + h, y_{n+1})) */
static const double dp5_e[7] = {71.0 / 57600.0,  0.0,          -71.0 / 16695.0, 71.0 / 1920.0,
                                -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0};
/* dense output of order 4 (HNW II.6, Hairer's DOPRI5: d1, d3..d7) */
static const double dp5_d[7] = {-12715105075.0 / 11282082432.0, 0.0,
                                87487479700.0 / 32700410799.0,  -10690763975.0 / 1880347072.0,
                                701980252875.0 / 199316789632.0, -1453857185.0 / 822651844.0,
                                69997945.0 / 29380423.0};

static const rk_tab tab_dp5 = {
    "dp5", 6, 7, 5, 0.2 - 0.04 * 0.75, 0.04, 0.2, 10.0, 3.25, dp5_c, dp5_a, dp5_b,
};

/* DOP853: Hairer's dop853.f (HNW I, II.10), c, a, b of the 12-stage 8th-order method, the
 * FSAL stage (index 12) and the three stages of the 7th-order dense output (13..15). */
static const double dop853_c[16] = {0.0,
                                    0.526001519587677318785587544488e-01,
                                    0.789002279381515978178381316732e-01,
                                    0.118350341907227396726757197510,
                                    0.281649658092772603273242802490,
                                    0.333333333333333333333333333333,
                                    0.25,
                                    0.307692307692307692307692307692,
                                    0.651282051282051282051282051282,
                                    0.6,
                                    0.857142857142857142857142857142,
                                    1.0,
                                    1.0,
                                    0.1,
                                    0.2,
                                    0.777777777777777777777777777778};
static const double dop853_a[ERK_MAX_STAGES * ERK_MAX_STAGES] = {
    A(1, 0) = 5.26001519587677318785587544488e-2,
    A(2, 0) = 1.97250569845378994544595329183e-2, A(2, 1) = 5.91751709536136983633785987549e-2,
    A(3, 0) = 2.95875854768068491816892993775e-2, A(3, 2) = 8.87627564304205475450678981324e-2,
    A(4, 0) = 2.41365134159266685502369798665e-1, A(4, 2) = -8.84549479328286085344864962717e-1,
    A(4, 3) = 9.24834003261792003115737966543e-1,
    A(5, 0) = 3.7037037037037037037037037037e-2, A(5, 3) = 1.70828608729473871279604482173e-1,
    A(5, 4) = 1.25467687566822425016691814123e-1,
    A(6, 0) = 3.7109375e-2, A(6, 3) = 1.70252211019544039314978060272e-1,
    A(6, 4) = 6.02165389804559606850219397283e-2, A(6, 5) = -1.7578125e-2,
    A(7, 0) = 3.70920001185047927108779319836e-2, A(7, 3) = 1.70383925712239993810214054705e-1,
    A(7, 4) = 1.07262030446373284651809199168e-1, A(7, 5) = -1.53194377486244017527936158236e-2,
    A(7, 6) = 8.27378916381402288758473766002e-3,
    A(8, 0) = 6.24110958716075717114429577812e-1, A(8, 3) = -3.36089262944694129406857109825,
    A(8, 4) = -8.68219346841726006818189891453e-1, A(8, 5) = 2.75920996994467083049415600797e1,
    A(8, 6) = 2.01540675504778934086186788979e1, A(8, 7) = -4.34898841810699588477366255144e1,
    A(9, 0) = 4.77662536438264365890433908527e-1, A(9, 3) = -2.48811461997166764192642586468,
    A(9, 4) = -5.90290826836842996371446475743e-1, A(9, 5) = 2.12300514481811942347288949897e1,
    A(9, 6) = 1.52792336328824235832596922938e1, A(9, 7) = -3.32882109689848629194453265587e1,
    A(9, 8) = -2.03312017085086261358222928593e-2,
    A(10, 0) = -9.3714243008598732571704021658e-1, A(10, 3) = 5.18637242884406370830023853209,
    A(10, 4) = 1.09143734899672957818500254654, A(10, 5) = -8.14978701074692612513997267357,
    A(10, 6) = -1.85200656599969598641566180701e1, A(10, 7) = 2.27394870993505042818970056734e1,
    A(10, 8) = 2.49360555267965238987089396762, A(10, 9) = -3.0467644718982195003823669022,
    A(11, 0) = 2.27331014751653820792359768449, A(11, 3) = -1.05344954667372501984066689879e1,
    A(11, 4) = -2.00087205822486249909675718444, A(11, 5) = -1.79589318631187989172765950534e1,
    A(11, 6) = 2.79488845294199600508499808837e1, A(11, 7) = -2.85899827713502369474065508674,
    A(11, 8) = -8.87285693353062954433549289258, A(11, 9) = 1.23605671757943030647266201528e1,
    A(11, 10) = 6.43392746015763530355970484046e-1,
    /* row 12 is b (the FSAL stage's argument is y_{n+1}): dop853_b below */
    A(13, 0) = 5.61675022830479523392909219681e-2, A(13, 6) = 2.53500210216624811088794765333e-1,
    A(13, 7) = -2.46239037470802489917441475441e-1,
    A(13, 8) = -1.24191423263816360469010140626e-1, A(13, 9) = 1.5329179827876569731206322685e-1,
    A(13, 10) = 8.20105229563468988491666602057e-3,
    A(13, 11) = 7.56789766054569976138603589584e-3, A(13, 12) = -8.298e-3,
    A(14, 0) = 3.18346481635021405060768473261e-2, A(14, 5) = 2.83009096723667755288322961402e-2,
    A(14, 6) = 5.35419883074385676223797384372e-2, A(14, 7) = -5.49237485713909884646569340306e-2,
    A(14, 10) = -1.08347328697249322858509316994e-4,
    A(14, 11) = 3.82571090835658412954920192323e-4,
    A(14, 12) = -3.40465008687404560802977114492e-4,
    A(14, 13) = 1.41312443674632500278074618366e-1,
    A(15, 0) = -4.28896301583791923408573538692e-1, A(15, 5) = -4.69762141536116384314449447206,
    A(15, 6) = 7.68342119606259904184240953878, A(15, 7) = 4.06898981839711007970213554331,
    A(15, 8) = 3.56727187455281109270669543021e-1,
    A(15, 12) = -1.39902416515901462129418009734e-3, A(15, 13) = 2.9475147891527723389556272149,
    A(15, 14) = -9.15095847217987001081870187138,
#undef A
};
static const double dop853_b[12] = {5.42937341165687622380535766363e-2, 0.0, 0.0, 0.0, 0.0,
                                    4.45031289275240888144113950566,
                                    1.89151789931450038304281599044,
                                    -5.8012039600105847814672114227,
                                    3.1116436695781989440891606237e-1,
                                    -1.52160949662516078556178806805e-1,
                                    2.01365400804030348374776537501e-1,
                                    4.47106157277725905176885569043e-2};
/* error estimators (dop853.f er1..er12 and bhh1..bhh3): the 5th-order one e5 and the 3rd-order
 * one e3 = b - bhh (bhh on stages 0, 8, 11), combined as in HNW II.10 (10.x) */
static const double dop853_e5[12] = {0.1312004499419488073250102996e-1, 0.0, 0.0, 0.0, 0.0,
                                     -0.1225156446376204440720569753e+1,
                                     -0.4957589496572501915214079952,
                                     0.1664377182454986536961530415e+1,
                                     -0.3503288487499736816886487290,
                                     0.3341791187130174790297318841,
                                     0.8192320648511571246570742613e-1,
                                     -0.2235530786388629525884427845e-1};
static const double dop853_bhh[3] = {0.244094488188976377952755905512,
                                     0.733846688281611857341361741547,
                                     0.220588235294117647058823529412e-1};
/* dense output (dop853.f d41..d716): rows for the coefficient vectors 4..7 over stages 0..15 */
static const double dop853_d[4][16] = {
    {-0.84289382761090128651353491142e+1, 0, 0, 0, 0, 0.56671495351937776962531783590,
     -0.30689499459498916912797304727e+1, 0.23846676565120698287728149680e+1,
     0.21170345824450282767155149946e+1, -0.87139158377797299206789907490,
     0.22404374302607882758541771650e+1, 0.63157877876946881815570249290,
     -0.88990336451333310820698117400e-1, 0.18148505520854727256656404962e+2,
     -0.91946323924783554000451984436e+1, -0.44360363875948939664310572000e+1},
    {0.10427508642579134603413151009e+2, 0, 0, 0, 0, 0.24228349177525818288430175319e+3,
     0.16520045171727028198505394887e+3, -0.37454675472269020279518312152e+3,
     -0.22113666853125306036270938578e+2, 0.77334326684722638389603898808e+1,
     -0.30674084731089398182061213626e+2, -0.93321305264302278729567221706e+1,
     0.15697238121770843886131091075e+2, -0.31139403219565177677282850411e+2,
     -0.93529243588444783865713862664e+1, 0.35816841486394083752465898540e+2},
    {0.19985053242002433820987653617e+2, 0, 0, 0, 0, -0.38703730874935176555105901742e+3,
     -0.18917813819516756882830838328e+3, 0.52780815920542364900561016686e+3,
     -0.11573902539959630126141871134e+2, 0.68812326946963000169666922661e+1,
     -0.10006050966910838403183860980e+1, 0.77771377980534432092869265740,
     -0.27782057523535084065932004339e+1, -0.60196695231264120758267380846e+2,
     0.84320405506677161018159903784e+2, 0.11992291136182789328035130030e+2},
    {-0.25693933462703749003312586129e+2, 0, 0, 0, 0, -0.15418974869023643374053993627e+3,
     -0.23152937917604549567536039109e+3, 0.35763911791061412378285349910e+3,
     0.93405324183624310003907691704e+2, -0.37458323136451633156875139351e+2,
     0.10409964950896230045147246184e+3, 0.29840293426660503123344363579e+2,
     -0.43533456590011143754432175058e+2, 0.96324553959188282948394950600e+2,
     -0.39177261675615439165231486172e+2, -0.14972683625798562581422125276e+3}};

static const rk_tab tab_dop853 = {
    "dop853", 12, 16, 8, 1.0 / 8.0 - 0.04 * 0.2, 0.04, 1.0 / 3.0, 6.0, 6.1,
    dop853_c, dop853_a, dop853_b,
};

/* A linear combination of stages, sum_j w_j k_j, with the tableau's zero weights left out:
 * its nonzero weights and their stages in ascending order, gathered once when the integrator
 * is created (the sums below are those of the tableau's rows, term for term). */
typedef struct rk_sum {
    int n;
    int j[ERK_MAX_STAGES];
    double w[ERK_MAX_STAGES];
} rk_sum;

static void rk_sum_init(rk_sum *sm, const double *w, int len)
{
    sm->n = 0;
    for (int j = 0; j < len; j++)
        if (w[j] != 0.0) {
            sm->j[sm->n] = j;
            sm->w[sm->n++] = w[j];
        }
}

/* sum_j w_j k_j[m] */
static double rk_sum_at(const rk_sum *sm, double *const *k, size_t m)
{
    double acc = 0.0;
    for (int q = 0; q < sm->n; q++)
        acc += sm->w[q] * k[sm->j[q]][m];
    return acc;
}

/* ---- the integrator's state ------------------------------------------------------ */

struct lv_erk {
    lv_integ_problem p; /* atol, rtol_v, g_dir borrowed */
    const rk_tab *tab;
    int dop853;
    size_t n, ng;
    size_t n_ctl;    /* states under error control: n less the quadratures */
    double t;        /* t_n: end of the last accepted step */
    double h;        /* the next step to try (> 0) */
    double t_old, h_old; /* the last accepted step [t_old, t_old + h_old] */
    int have_step;   /* a step exists: the dense output covers [t_old, t] */
    int dense_ready; /* its dense-output coefficients are computed */
    int fsal;        /* k[s] holds f(t, y) of the step just accepted: the next step's k[0] */
    double t_lo;     /* the time of the last return: events are searched after it */
    double tstop;
    int has_tstop;
    double facold;   /* PI controller: last accepted error (>= 1e-4) */
    int rejected;    /* the last attempt was rejected: no increase of h */
    int iasti, nonsti, stiff; /* stiffness test counters, the verdict */
    double t_stiff;
    /* The event functions at the end of the last accepted step, evaluated once per step
     * (g_end_ok). A step over which none of them changes sign against g_lo (step_clear) needs
     * no evaluation at the returns inside it: as in CVODE, a function is sampled at the steps'
     * ends, and a sign change is searched for only in a step that shows one. */
    int g_end_ok, step_clear;
    long steps, rhs_step, rhs_dense, fails, g_evals;
    lv_integ_pace pace; /* the step-size collapse check (integrator.h) */
    /* arrays, one allocation */
    double *y, *yold, *ynew, *ysti, *ytmp, *sk;
    double *k[ERK_MAX_STAGES];
    double *rc[ERK_MAX_RC];
    double *g_lo, *g_b, *g_m; /* [ng] at t_lo (in a clear step: at its start), at the
                               * bracket's right end, at an iterate */
    double *g_end;            /* [ng] at the step's end t (g_end_ok) */
    double *g_s;              /* [ng] at the step's start t_s */
    double t_s;               /* the start of the step being returned (= t_old once taken) */
    /* the tableau's sums without their zero terms (rk_sum): stage arguments (rows of a), the
     * solution (b), dp5's error estimate (e), the dense output's coefficients (d) */
    rk_sum a_sum[ERK_MAX_STAGES], b_sum, e_sum, d_sum[4];
    double *x_b, *x_m;        /* [n] states there */
    double *mem;
};

/* 1 where a state is a quadrature, out of the error control (lv_integ_problem.quad). */
static int is_quad(const lv_erk *e, size_t i) { return e->p.quad != NULL && e->p.quad[i]; }

static double rtol_of(const lv_erk *e, size_t i)
{
    return e->p.rtol_v != NULL ? e->p.rtol_v[i] : e->p.rtol;
}

/* The model's rhs, counted: on the steps, or for the dense output. */
static int call_f(lv_erk *e, double t, const double *x, double *f, int dense)
{
    if (dense)
        e->rhs_dense++;
    else
        e->rhs_step++;
    return e->p.rhs(t, x, f, e->p.user);
}

static int call_g(lv_erk *e, double t, const double *x, double *g)
{
    e->g_evals++;
    return e->p.g(t, x, g, e->p.user);
}

/* ---- creation --------------------------------------------------------------------- */

lv_status lv_erk_create(const lv_integ_problem *p, int dop853, double t0, const double *x0,
                        lv_erk **out, lv_err *err)
{
    *out = NULL;
    lv_erk *e = calloc(1, sizeof *e);
    if (e == NULL)
        return lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
    e->p = *p;
    e->pace = (lv_integ_pace){t0, t0, 0, p->max_steps};
    e->dop853 = dop853;
    e->tab = dop853 ? &tab_dop853 : &tab_dp5;
    e->n = p->n;
    e->ng = p->n_g;
    e->n_ctl = 0;
    for (size_t i = 0; i < p->n; i++)
        e->n_ctl += !is_quad(e, i);
    if (e->n_ctl == 0)
        e->n_ctl = p->n; /* refused by lv_integ_create; never a division by zero */
    const size_t n = e->n, ng = e->ng;
    const size_t nk = (size_t)e->tab->s_dense, nrc = dop853 ? 8 : 5;
    const size_t total = n * (6 + nk + nrc + 2) + 5 * ng;
    e->mem = calloc(total ? total : 1, sizeof *e->mem);
    if (e->mem == NULL) {
        free(e);
        return lv_fail(err, LV_ERR_NOMEM, "integrator: out of memory");
    }
    double *m = e->mem;
    e->y = m, m += n;
    e->yold = m, m += n;
    e->ynew = m, m += n;
    e->ysti = m, m += n;
    e->ytmp = m, m += n;
    e->sk = m, m += n;
    for (size_t j = 0; j < nk; j++)
        e->k[j] = m, m += n;
    for (size_t j = 0; j < nrc; j++)
        e->rc[j] = m, m += n;
    e->x_b = m, m += n;
    e->x_m = m, m += n;
    e->g_lo = m, m += ng;
    e->g_b = m, m += ng;
    e->g_m = m, m += ng;
    e->g_end = m, m += ng;
    e->g_s = m, m += ng;
    for (size_t i = 1; i < nk; i++)
        rk_sum_init(&e->a_sum[i], e->tab->a + i * ERK_MAX_STAGES, (int)i);
    rk_sum_init(&e->b_sum, e->tab->b, e->tab->s);
    if (dop853) {
        for (int r = 0; r < 4; r++)
            rk_sum_init(&e->d_sum[r], dop853_d[r], 16);
    } else {
        rk_sum_init(&e->e_sum, dp5_e, 7);
        rk_sum_init(&e->d_sum[0], dp5_d, 7);
    }
    lv_status st = lv_erk_restart(e, t0, x0, err);
    if (st != LV_OK) {
        lv_erk_free(e);
        return st;
    }
    *out = e;
    return LV_OK;
}

void lv_erk_free(lv_erk *e)
{
    if (e == NULL)
        return;
    free(e->mem);
    free(e);
}

double lv_erk_time(const lv_erk *e) { return e->t_lo; }

int lv_erk_stiff(const lv_erk *e, double *t_detected)
{
    if (t_detected != NULL)
        *t_detected = e->t_stiff;
    return e->stiff;
}

void lv_erk_get_stats(const lv_erk *e, lv_integ_stats *st)
{
    memset(st, 0, sizeof *st);
    st->steps = e->steps;
    st->rhs_step = e->rhs_step;
    st->rhs_dense = e->rhs_dense;
    st->rhs_evals = e->rhs_step + e->rhs_dense;
    st->err_test_fails = e->fails;
    st->g_evals = e->g_evals;
}

lv_status lv_erk_set_stop_time(lv_erk *e, double tstop, lv_err *err)
{
    if (!(tstop > e->t_lo))
        return lv_fail(err, LV_ERR_SOLVER, "integrator: stop time %.17g is not after t = %.17g",
                       tstop, e->t_lo);
    /* a step already past it (the caller moved the stop time back): the step is taken back
     * (its start state and first stage are kept) and taken again to the stop time */
    if (e->have_step && e->t > tstop) {
        double *tmp = e->y;
        e->y = e->yold;
        e->yold = tmp;
        e->t = e->t_old;
        e->fsal = 0;
        e->have_step = 0;
        e->dense_ready = 0;
        e->g_end_ok = 0;
        if (e->h > e->h_old)
            e->h = e->h_old;
    }
    e->tstop = tstop;
    e->has_tstop = 1;
    return LV_OK;
}

/* HNW I, II.4, "Starting Step Size": an Euler step of size h0 = 0.01 ||y0|| / ||f0|| estimates
 * the second derivative; h1 = (0.01 / max(||f0||, ||y''||))^(1/q); h = min(100 h0, h1). With
 * Hairer's norms (no division by n). Returns the rhs status of the trial evaluation. */
static int initial_step(lv_erk *e, double hmax, double *h_out)
{
    const size_t n = e->n;
    const double *y = e->y, *f0 = e->k[0];
    double dnf = 0.0, dny = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double sk = e->p.atol[i] + rtol_of(e, i) * fabs(y[i]);
        e->sk[i] = sk;
        if (is_quad(e, i))
            continue;
        dnf += (f0[i] / sk) * (f0[i] / sk);
        dny += (y[i] / sk) * (y[i] / sk);
    }
    double h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : sqrt(dny / dnf) * 0.01;
    if (h > hmax)
        h = hmax;
    for (size_t i = 0; i < n; i++)
        e->ytmp[i] = y[i] + h * f0[i];
    double *f1 = e->k[1];
    const int rc = call_f(e, e->t + h, e->ytmp, f1, 0);
    if (rc != 0)
        return rc;
    double der2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (is_quad(e, i))
            continue;
        const double d = (f1[i] - f0[i]) / e->sk[i];
        der2 += d * d;
    }
    der2 = sqrt(der2) / h;
    const double der12 = fmax(fabs(der2), sqrt(dnf));
    const double h1 = der12 <= 1e-15 ? fmax(1e-6, h * 1e-3)
                                     : pow(0.01 / der12, 1.0 / (double)e->tab->order);
    h = fmin(fmin(100.0 * h, h1), hmax);
    *h_out = h;
    return 0;
}

lv_status lv_erk_restart(lv_erk *e, double t, const double *x, lv_err *err)
{
    memcpy(e->y, x, e->n * sizeof *x);
    e->t = e->t_lo = t;
    e->have_step = e->dense_ready = e->fsal = 0;
    e->g_end_ok = 0;
    e->has_tstop = 0;
    e->facold = 1e-4;
    e->rejected = 0;
    e->h = 0.0; /* chosen by initial_step before the first step */
    e->iasti = e->nonsti = 0; /* a stiff verdict stays: it is about the problem */
    int rc = call_f(e, t, e->y, e->k[0], 0);
    if (rc != 0)
        return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: right-hand side failed at the first "
                       "call [%s]", t, e->tab->name);
    if (e->ng > 0 && call_g(e, t, e->y, e->g_lo) != 0)
        return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: event function failed [%s]", t,
                       e->tab->name);
    return LV_OK;
}

/* ---- one step --------------------------------------------------------------------- */

/* Stages 1 .. s of a step of size h from (t, y) with k[0] = f(t, y): y_{n+1} in ynew, the
 * argument of stage s-1 (c = 1) in ysti. Returns the first nonzero rhs status. */
static int rk_stages(lv_erk *e, double h, double t_end)
{
    const rk_tab *T = e->tab;
    const size_t n = e->n;
    const int s = T->s;
    for (int i = 1; i < s; i++) {
        double *arg = (i == s - 1) ? e->ysti : e->ytmp;
        for (size_t m = 0; m < n; m++)
            arg[m] = e->y[m] + h * rk_sum_at(&e->a_sum[i], e->k, m);
        /* a stage at c = 1 is at t_end exactly: the stop time is never passed by round-off */
        const double ti = T->c[i] == 1.0 ? t_end : e->t + T->c[i] * h;
        const int rc = call_f(e, ti, arg, e->k[i], 0);
        if (rc != 0)
            return rc;
    }
    for (size_t m = 0; m < n; m++)
        e->ynew[m] = e->y[m] + h * rk_sum_at(&e->b_sum, e->k, m);
    /* the FSAL stage at t + h: exactly the stop time when the step ends there */
    return call_f(e, t_end, e->ynew, e->k[s], 0);
}

/* The scaled error of the step (HNW II.4 (4.11); DOP853: II.10, the 5th- and 3rd-order
 * estimates combined as err5^2 / sqrt(err5^2 + 0.01 err3^2)). */
static double rk_error(lv_erk *e, double h)
{
    const size_t n = e->n;
    double err = 0.0;
    for (size_t i = 0; i < n; i++)
        e->sk[i] = e->p.atol[i] + rtol_of(e, i) * fmax(fabs(e->y[i]), fabs(e->ynew[i]));
    if (!e->dop853) {
        for (size_t i = 0; i < n; i++) {
            if (is_quad(e, i))
                continue;
            double d = rk_sum_at(&e->e_sum, e->k, i);
            d = h * d / e->sk[i];
            err += d * d;
        }
        return sqrt(err / (double)e->n_ctl);
    }
    double err2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (is_quad(e, i))
            continue;
        double bk = 0.0, e5 = 0.0;
        for (int j = 0; j < 12; j++) {
            bk += dop853_b[j] * e->k[j][i];
            e5 += dop853_e5[j] * e->k[j][i];
        }
        const double e3 = bk - dop853_bhh[0] * e->k[0][i] - dop853_bhh[1] * e->k[8][i] -
                          dop853_bhh[2] * e->k[11][i];
        err2 += (e3 / e->sk[i]) * (e3 / e->sk[i]);
        err += (e5 / e->sk[i]) * (e5 / e->sk[i]);
    }
    double deno = err + 0.01 * err2;
    if (!(deno > 0.0))
        deno = 1.0;
    return fabs(h) * err / sqrt(deno * (double)e->n_ctl);
}

/* Hairer's stiffness test after an accepted step (HNW IV.2): h lambda estimated from the two
 * stages at c = 1, ||f(y_{n+1}) - f(ysti)|| / ||y_{n+1} - ysti||. */
static void stiffness_test(lv_erk *e, double h)
{
    const size_t n = e->n;
    const int s = e->tab->s;
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (is_quad(e, i))
            continue;
        const double df = e->k[s][i] - e->k[s - 1][i], dy = e->ynew[i] - e->ysti[i];
        num += df * df;
        den += dy * dy;
    }
    if (!(den > 0.0))
        return;
    const double hlamb = h * sqrt(num / den);
    if (hlamb > e->tab->hlamb_max) {
        e->nonsti = 0;
        if (++e->iasti == 15 && !e->stiff) {
            e->stiff = 1;
            e->t_stiff = e->t + h;
        }
    } else if (++e->nonsti == 6) {
        e->iasti = 0;
    }
}

/* Takes one accepted step from e->t (retrying rejected ones). */
static lv_status rk_step(lv_erk *e, lv_err *err)
{
    const rk_tab *T = e->tab;
    if (e->steps >= e->p.max_steps)
        return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: too much work (%ld steps allowed) [%s]",
                       e->t, e->p.max_steps, T->name);
    if (e->fsal) { /* the last step's f(t_{n+1}, y_{n+1}) is this one's first stage */
        double *tmp = e->k[0];
        e->k[0] = e->k[T->s];
        e->k[T->s] = tmp;
        e->fsal = 0;
    }
    double hmax = e->p.max_step > 0.0 ? e->p.max_step : INFINITY;
    if (e->has_tstop && e->tstop - e->t < hmax)
        hmax = e->tstop - e->t;
    if (e->h == 0.0 && e->p.init_step > 0.0)
        e->h = e->p.init_step;
    if (e->h == 0.0) {
        const int rc = initial_step(e, hmax, &e->h);
        if (rc < 0)
            return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: right-hand side failed "
                           "unrecoverably [%s]", e->t, T->name);
        if (rc > 0)
            e->h = 1e-3 * hmax < 1e-6 ? 1e-3 * hmax : 1e-6;
    }
    int rhs_fails = 0;
    for (;;) {
        double h = e->h > hmax ? hmax : e->h;
        int to_stop = 0;
        /* no sliver of a step left before the stop time (Hairer: x + 1.01 h beyond xend) */
        if (e->has_tstop && e->t + 1.01 * h >= e->tstop) {
            h = e->tstop - e->t;
            to_stop = 1;
        }
        if (!(h > 0.0) || (!to_stop && !(h > 16.0 * DBL_EPSILON * fabs(e->t))))
            return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: step size underflow (h = %g) "
                           "[%s]", e->t, h, T->name);
        const double t_end = to_stop ? e->tstop : e->t + h;
        int rc = rk_stages(e, h, t_end);
        if (rc < 0)
            return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: right-hand side failed "
                           "unrecoverably [%s]", e->t, T->name);
        if (rc > 0) { /* a state the model cannot accept: retry smaller (ARKODE: 0.25) */
            if (++rhs_fails > 10)
                return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: right-hand side failed "
                               "repeatedly (state not acceptable) [%s]", e->t, T->name);
            e->fails++;
            e->h = 0.25 * h;
            e->rejected = 1;
            continue;
        }
        const double errn = rk_error(e, h);
        if (!isfinite(errn)) {
            e->fails++;
            e->h = 0.25 * h;
            e->rejected = 1;
            if (++rhs_fails > 10)
                return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: error estimate not finite "
                               "[%s]", e->t, T->name);
            continue;
        }
        /* PI controller (HNW II.4 (4.13) with Gustafsson's stabilisation, IV.2) */
        const double fac11 = pow(errn, T->expo1);
        if (errn <= 1.0) {
            double fac = fac11 / pow(e->facold, T->beta);
            fac = fmax(1.0 / T->fac_max, fmin(1.0 / T->fac_min, fac / 0.9));
            double hnew = h / fac;
            if (e->rejected && hnew > h)
                hnew = h;
            e->facold = fmax(errn, 1e-4);
            e->rejected = 0;
            /* accept */
            e->steps++;
            stiffness_test(e, h);
            double *tmp = e->yold;
            e->yold = e->y;
            e->y = e->ynew;
            e->ynew = tmp;
            e->t_old = e->t;
            e->h_old = h;
            e->t = t_end;
            e->have_step = 1;
            e->dense_ready = 0;
            e->g_end_ok = 0;
            e->fsal = 1;
            e->h = hnew;
            if (e->steps - e->pace.n_mark >= LV_INTEG_PACE_WINDOW) { /* a window's end */
                char why[LV_ERR_MSG_MAX - 16];
                if (lv_integ_pace_collapsed(&e->pace, e->t, e->steps, why, sizeof why))
                    return lv_fail(err, LV_ERR_SOLVER, "%s [%s]", why, T->name);
            }
            return LV_OK;
        }
        e->fails++;
        e->rejected = 1;
        e->h = h / fmin(1.0 / T->fac_min, fac11 / 0.9);
    }
}

/* ---- dense output ----------------------------------------------------------------- */

/* The coefficients of the last step's continuous extension (HNW II.6 for DOPRI5, II.10 for
 * DOP853, in Hairer's form y(t_old + theta h) = rc0 + theta (rc1 + (1-theta)(rc2 + theta (rc3
 * + (1-theta) ...)))). DOP853 first evaluates its three extra stages (counted as dense). */
static int dense_prepare(lv_erk *e)
{
    const size_t n = e->n;
    const int s = e->tab->s;
    const double h = e->h_old;
    const double *y0 = e->yold, *y1 = e->y, *k0 = e->k[0], *ks = e->k[s];
    if (e->dop853) {
        for (int i = 13; i < 16; i++) {
            for (size_t m = 0; m < n; m++)
                e->ytmp[m] = y0[m] + h * rk_sum_at(&e->a_sum[i], e->k, m);
            const int rc = call_f(e, e->t_old + dop853_c[i] * h, e->ytmp, e->k[i], 1);
            if (rc != 0)
                return rc;
        }
    }
    for (size_t m = 0; m < n; m++) {
        const double dy = y1[m] - y0[m], bspl = h * k0[m] - dy;
        e->rc[0][m] = y0[m];
        e->rc[1][m] = dy;
        e->rc[2][m] = bspl;
        e->rc[3][m] = dy - h * ks[m] - bspl;
    }
    if (e->dop853) {
        for (int r = 0; r < 4; r++)
            for (size_t m = 0; m < n; m++)
                e->rc[4 + r][m] = h * rk_sum_at(&e->d_sum[r], e->k, m);
    } else {
        for (size_t m = 0; m < n; m++)
            e->rc[4][m] = h * rk_sum_at(&e->d_sum[0], e->k, m);
    }
    e->dense_ready = 1;
    return 0;
}

/* The state at time t of the last step, into x: the step's end exactly at its end. */
static int dense_eval(lv_erk *e, double t, double *x)
{
    const size_t n = e->n;
    if (t == e->t) {
        memcpy(x, e->y, n * sizeof *x);
        return 0;
    }
    if (!e->dense_ready) {
        const int rc = dense_prepare(e);
        if (rc != 0)
            return rc;
    }
    const double th = (t - e->t_old) / e->h_old, th1 = 1.0 - th;
    double *const *rc = e->rc;
    if (e->dop853) {
        for (size_t m = 0; m < n; m++) {
            const double conpar = rc[4][m] + th * (rc[5][m] + th1 * (rc[6][m] + th * rc[7][m]));
            x[m] = rc[0][m] +
                   th * (rc[1][m] + th1 * (rc[2][m] + th * (rc[3][m] + th1 * conpar)));
        }
    } else {
        for (size_t m = 0; m < n; m++)
            x[m] = rc[0][m] +
                   th * (rc[1][m] + th1 * (rc[2][m] + th * (rc[3][m] + th1 * rc[4][m])));
    }
    return 0;
}

/* ---- events ----------------------------------------------------------------------- */

static int sgn(double v) { return v > 0.0 ? 1 : v < 0.0 ? -1 : 0; }

/* Function i crosses between a value glo (at the last return; 0 there: inactive until it
 * leaves 0, which is no crossing) and g, in a direction it asks for. */
static int crosses(const lv_erk *e, size_t i, double glo, double g)
{
    if (glo == 0.0 || sgn(g) == sgn(glo))
        return 0;
    const int dir = glo < 0.0 ? 1 : -1, want = e->p.g_dir != NULL ? e->p.g_dir[i] : 0;
    return want == 0 || want == dir;
}

/* A root's time tolerance: CVODE's 100 eps (|t| + |h|). */
static double root_ttol(const lv_erk *e)
{
    return 100.0 * DBL_EPSILON * (fabs(e->t) + fabs(e->h_old));
}

/* The earliest root in (ta0, thi] of the functions that cross there, g_a0 holding g(ta0), g_b
 * g(thi) and x_b the state at thi: each crossing function's root bracketed by the Illinois
 * variant of regula falsi (Dowell & Jarratt 1971) on the dense output, down to CVODE's time
 * tolerance 100 eps (|t| + |h|); the bracket's right end (where the function has crossed)
 * becomes the new thi for the functions after it. On return *tb is that time and g_b, x_b the
 * values there. Returns 0, or the status of a failed evaluation (< 0: g, > 0: the dense
 * output). */
static int locate_root(lv_erk *e, double ta0, const double *g_a0, double *tb_io)
{
    const size_t ng = e->ng;
    const double ttol = root_ttol(e);
    double tb = *tb_io;
    for (size_t i = 0; i < ng; i++) {
        if (!crosses(e, i, g_a0[i], e->g_b[i]))
            continue;
        double ta = ta0, fa = g_a0[i], fb = e->g_b[i];
        int side = 0;
        for (int it = 0; it < 200 && tb - ta > ttol && fb != 0.0; it++) {
            double tm = tb - fb * (tb - ta) / (fb - fa);
            const double lo = ta + 0.5 * ttol, hi = tb - 0.5 * ttol;
            if (!(tm > lo))
                tm = lo;
            if (!(tm < hi))
                tm = hi;
            int rc = dense_eval(e, tm, e->x_m);
            if (rc != 0)
                return 1;
            if (call_g(e, tm, e->x_m, e->g_m) != 0)
                return -1;
            const double fm = e->g_m[i];
            if (sgn(fm) != sgn(fa)) { /* crossed by tm: [ta, tm] */
                tb = tm;
                fb = fm;
                memcpy(e->g_b, e->g_m, ng * sizeof *e->g_b);
                memcpy(e->x_b, e->x_m, e->n * sizeof *e->x_b);
                if (side == 1)
                    fa *= 0.5;
                side = 1;
            } else { /* [tm, tb] */
                ta = tm;
                fa = fm;
                if (side == -1)
                    fb *= 0.5;
                side = -1;
            }
        }
    }
    *tb_io = tb;
    return 0;
}

/* The earliest root in (t_lo, thi] (a crossing is there: g_b holds g(thi), x_b the state),
 * located so that it does not depend on the returns inside the step: where every function
 * that crosses in (t_lo, thi] also crosses between the step's two ends, the brackets start
 * from the whole step [t_s, t] (g_s, g_end), whatever output times were returned inside it,
 * and the root found is kept if it lies in (t_lo, thi]. Otherwise (a function that crosses
 * back and forth inside the step, or a root before the last return) from (t_lo, thi]. So a
 * run that writes no rows and skips its output times (sim/simulate.c, grid_skipped), a
 * stop at lv_sim_advance's time or an FMU's communication point locate the same event time
 * bit for bit as a run that returns at every output time. Returns as locate_root, or
 * LOC_AFTER: the whole step's root lies after thi by less than the time tolerance (the
 * crossing thi shows is that root, on an output time): no root up to thi. */
#define LOC_AFTER 2 /* locate_in_step: the root lies just after thi */

static int locate_in_step(lv_erk *e, double thi, double *tb_io)
{
    int whole = 1;
    for (size_t i = 0; i < e->ng && whole; i++)
        if (crosses(e, i, e->g_lo[i], e->g_b[i]))
            whole = crosses(e, i, e->g_s[i], e->g_end[i]);
    if (whole) {
        double tb = e->t;
        memcpy(e->g_b, e->g_end, e->ng * sizeof *e->g_b);
        memcpy(e->x_b, e->y, e->n * sizeof *e->x_b);
        const int rc = locate_root(e, e->t_s, e->g_s, &tb);
        if (rc != 0)
            return rc;
        if (tb > e->t_lo && tb <= thi) {
            *tb_io = tb;
            return 0;
        }
        /* the root the crossing at thi shows, located from the whole step, lies just after
         * thi (a root on an output time: an end whose value is a row's value is 0 at thi and
         * within round-off of 0 for some 1e-12 s around it, so the window is 100 times the
         * time tolerance): thi is returned as it is, and the root is found again after it,
         * as a run without that output time finds it (the caller keeps g_lo from before the
         * crossing) */
        const double ttol = root_ttol(e);
        if (tb > thi && tb - thi <= 100.0 * ttol)
            return LOC_AFTER;
        /* back to (t_lo, thi]: g_b and x_b at thi again */
        if (dense_eval(e, thi, e->x_b) != 0)
            return 1;
        if (thi == e->t)
            memcpy(e->g_b, e->g_end, e->ng * sizeof *e->g_b);
        else if (call_g(e, thi, e->x_b, e->g_b) != 0)
            return -1;
    }
    *tb_io = thi;
    return locate_root(e, e->t_lo, e->g_lo, tb_io);
}

/* ---- advance ---------------------------------------------------------------------- */

lv_status lv_erk_advance(lv_erk *e, double tout, int stop_on_stiff, double *t, double *x,
                         int *res, int *roots, lv_err *err)
{
    const char *name = e->tab->name;
    double tend = tout;
    if (e->has_tstop && tend > e->tstop)
        tend = e->tstop;
    *t = e->t_lo;
    if (!(tend > e->t_lo)) {
        memcpy(x, e->y, e->n * sizeof *x);
        if (tend == e->t_lo && e->t_lo == e->t) {
            *res = LV_INTEG_REACHED;
            return LV_OK;
        }
        return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: output time %.17g is not after the "
                       "time reached [%s]", e->t_lo, tout, name);
    }
    for (;;) {
        if (e->t_lo < e->t) {
            /* the part of the last step not yet returned: (t_lo, min(t_n, tend)] */
            const double thi = e->t < tend ? e->t : tend;
            if (e->ng > 0 && !e->g_end_ok) { /* once per step: at its end, where x = y */
                if (call_g(e, e->t, e->y, e->g_end) != 0)
                    return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: event function failed "
                                   "[%s]", e->t, name);
                e->g_end_ok = 1;
                e->step_clear = 1;
                for (size_t i = 0; i < e->ng && e->step_clear; i++)
                    e->step_clear = !crosses(e, i, e->g_lo[i], e->g_end[i]);
            }
            if (dense_eval(e, thi, e->x_b) != 0)
                return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: right-hand side failed in "
                               "the dense output [%s]", e->t_lo, name);
            if (e->ng > 0 && !e->step_clear) {
                if (thi == e->t)
                    memcpy(e->g_b, e->g_end, e->ng * sizeof *e->g_b);
                else if (call_g(e, thi, e->x_b, e->g_b) != 0)
                    return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: event function failed "
                                   "[%s]", thi, name);
                int any = 0;
                for (size_t i = 0; i < e->ng && !any; i++)
                    any = crosses(e, i, e->g_lo[i], e->g_b[i]);
                if (any) {
                    double tb = thi;
                    const int rc = locate_in_step(e, thi, &tb);
                    if (rc == LOC_AFTER) {
                        /* no root up to thi: thi is returned, g_lo keeps its values from
                         * before the crossing, so that the next return finds the root just
                         * after thi */
                        if (dense_eval(e, thi, e->x_b) != 0)
                            return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: right-hand side "
                                           "failed in the dense output [%s]", e->t_lo, name);
                        e->t_lo = thi;
                        memcpy(x, e->x_b, e->n * sizeof *x);
                        *t = thi;
                        *res = LV_INTEG_REACHED;
                        return LV_OK;
                    }
                    if (rc != 0)
                        return lv_fail(err, LV_ERR_SOLVER, "at t = %.9g s: %s failed while "
                                       "locating an event [%s]", e->t_lo,
                                       rc < 0 ? "event function" : "right-hand side", name);
                    for (size_t i = 0; i < e->ng; i++)
                        roots[i] = crosses(e, i, e->g_lo[i], e->g_b[i])
                                       ? (e->g_lo[i] < 0.0 ? 1 : -1)
                                       : 0;
                    memcpy(e->g_lo, e->g_b, e->ng * sizeof *e->g_lo);
                    memcpy(x, e->x_b, e->n * sizeof *x);
                    e->t_lo = tb;
                    *t = tb;
                    *res = LV_INTEG_ROOT;
                    return LV_OK;
                }
                memcpy(e->g_lo, e->g_b, e->ng * sizeof *e->g_lo);
            } else if (e->ng > 0 && thi == e->t) {
                /* a clear step returned to its end: g_lo is at t_lo again */
                memcpy(e->g_lo, e->g_end, e->ng * sizeof *e->g_lo);
            }
            e->t_lo = thi;
            if (thi == tend) {
                memcpy(x, e->x_b, e->n * sizeof *x);
                *t = thi;
                *res = LV_INTEG_REACHED;
                return LV_OK;
            }
        }
        if (stop_on_stiff && e->stiff) {
            memcpy(x, e->y, e->n * sizeof *x);
            *t = e->t;
            *res = LV_ERK_STIFF;
            return LV_OK;
        }
        e->t_s = e->t; /* the whole step was returned: g_lo is at its end, the next's start */
        if (e->ng > 0)
            memcpy(e->g_s, e->g_lo, e->ng * sizeof *e->g_s);
        lv_status st = rk_step(e, err);
        if (st != LV_OK) {
            memcpy(x, e->y, e->n * sizeof *x);
            *t = e->t;
            e->t_lo = e->t;
            return st;
        }
    }
}
