/* C client of the planetary drop-in (include/fsym.h, fsym_planets_*): the outer solar system
 * through the header's prototypes. Checks, exiting 1 on the first failure:
 *  - calls of 40 and 23 steps end bitwise where one call of 63 does;
 *  - a restart from copies of rw and iw (fsym_planets_state) continues bitwise;
 *  - a mass one ulp off is refused (FSYM_ERR_CHECKPOINT), x and v unchanged;
 *  - an extra force with user data is called, and a gradient method is refused with it;
 *  - the guard (fraction 1e-4) refuses, x and v unchanged;
 *  - a close encounter gives FSYM_ERR_ENCOUNTER, x and v unchanged, the pair in the message.
 * Build: cc c_planets.c -I<fsym>/include -lfsym -lgfortran -lm */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fsym.h"

#define N 5
static const double G = 2.95912208286e-4, M0 = 1.00000597682, H = 108.3;
static const double MS[N] = {0.000954786104043, 0.000285583733151, 0.0000437273164546,
                             0.0000517759138449, 7.692307692307693e-09};
static const double X0[N][3] = {{-3.5023653, -3.8169847, -1.5507963},
                                {9.0755314, -3.0458353, -1.6483708},
                                {8.3101420, -16.2901086, -7.2521278},
                                {11.4707666, -25.7294829, -10.8169456},
                                {-15.5387357, -25.2225594, -3.1902382}};
static const double V0[N][3] = {{0.00565429, -0.00412490, -0.00190589},
                                {0.00168318, 0.00483525, 0.00192462},
                                {0.00354178, 0.00137102, 0.00055029},
                                {0.00288930, 0.00114527, 0.00039677},
                                {0.00276725, -0.00170702, -0.00136504}};

static int fail(const char *what) {
    fprintf(stderr, "c_planets: FAILED: %s\n", what);
    return 1;
}

/* a uniform field; user: double[4] = field, call count */
static int field(int n, const double *x, double *a, void *user) {
    double *f = user;
    for (int k = 0; k < n; ++k)
        for (int i = 0; i < 3; ++i) a[3 * k + i] = f[i];
    f[3] += 1.0;
    (void)x;
    return 0;
}

static int setup(const char *method, int coords, int n, double m0, const double *m,
                 double g, double hill, double **rw, int *lrw, int **iw, int *liw) {
    if (fsym_planets_work_size(method, n, lrw, liw) != 0) return 1;
    *rw = malloc(sizeof(double) * (size_t)*lrw);
    *iw = malloc(sizeof(int) * (size_t)*liw);
    if (!*rw || !*iw) return 1;
    return fsym_planets_init(method, coords, n, m0, m, g, hill, *rw, *lrw, *iw, *liw);
}

int main(void) {
    double x[N][3], v[N][3], y[N][3], w[N][3], m[N], *rw, *rw2, *ck;
    int *iw, *iw2, *ick, lrw, liw, st;
    char msg[256];
    memcpy(m, MS, sizeof m);

    /* 40 + 23 steps = 63 steps, bitwise */
    if (setup("SRKN6b", FSYM_PLANETS_JACOBI, N, M0, m, G, 0.0, &rw, &lrw, &iw, &liw))
        return fail("setup");
    if (lrw != 30 + 13 * N + 2 * 13 + 3 * N * 4 || liw != 79 + 13) return fail("work sizes");
    memcpy(x, X0, sizeof x); memcpy(v, V0, sizeof v);
    st = fsym_planets_step(N, M0, m, G, &x[0][0], &v[0][0], H, 40, NULL, NULL, 0.0, rw, lrw,
                           iw, liw);
    if (st != 0) return fail("40 steps");
    ck = malloc(sizeof(double) * (size_t)lrw); ick = malloc(sizeof(int) * (size_t)liw);
    memcpy(ck, rw, sizeof(double) * (size_t)lrw); memcpy(ick, iw, sizeof(int) * (size_t)liw);
    st = fsym_planets_step(N, M0, m, G, &x[0][0], &v[0][0], H, 23, NULL, NULL, 0.0, rw, lrw,
                           iw, liw);
    if (st != 0) return fail("23 steps");
    if (setup("SRKN6b", FSYM_PLANETS_JACOBI, N, M0, m, G, 0.0, &rw2, &lrw, &iw2, &liw))
        return fail("setup 2");
    memcpy(y, X0, sizeof y); memcpy(w, V0, sizeof w);
    st = fsym_planets_step(N, M0, m, G, &y[0][0], &w[0][0], H, 63, NULL, NULL, 0.0, rw2, lrw,
                           iw2, liw);
    if (st != 0 || memcmp(x, y, sizeof x) || memcmp(v, w, sizeof v)) return fail("40 + 23");

    /* restart from the copies */
    st = fsym_planets_state(N, &y[0][0], &w[0][0], ck, lrw, ick, liw);
    if (st != 0) return fail("state");
    st = fsym_planets_step(N, M0, m, G, &y[0][0], &w[0][0], H, 23, NULL, NULL, 0.0, ck, lrw,
                           ick, liw);
    if (st != 0 || memcmp(x, y, sizeof x) || memcmp(v, w, sizeof v)) return fail("restart");

    /* a mass one ulp off: refused, nothing changed */
    m[2] = nextafter(m[2], 1.0);
    st = fsym_planets_step(N, M0, m, G, &y[0][0], &w[0][0], H, 5, NULL, NULL, 0.0, ck, lrw,
                           ick, liw);
    fsym_planets_message(st, ck, lrw, ick, liw, msg, (int)sizeof msg);
    if (st != FSYM_ERR_CHECKPOINT || memcmp(x, y, sizeof x) || !strstr(msg, "body 3"))
        return fail(msg);
    m[2] = MS[2];

    /* the guard */
    st = fsym_planets_step(N, M0, m, G, &y[0][0], &w[0][0], H, 5, NULL, NULL, 1.0e-4, ck, lrw,
                           ick, liw);
    if (st != FSYM_ERR_STEP_TOO_LARGE || memcmp(x, y, sizeof x)) return fail("guard");

    /* an extra force with user data; a gradient method refused with it */
    double f[4] = {1.0e-9, -2.0e-9, 3.0e-10, 0.0};
    double *rw3;
    int *iw3, lrw3, liw3;
    if (setup("C'", FSYM_PLANETS_JACOBI, N, M0, m, G, 0.0, &rw3, &lrw3, &iw3, &liw3))
        return fail("setup C'");
    st = fsym_planets_step(N, M0, m, G, &y[0][0], &w[0][0], H, 5, field, f, 0.0, rw3, lrw3,
                           iw3, liw3);
    if (st != 0 || f[3] < 1.0) return fail("extra force");
    free(rw3); free(iw3);
    if (setup("A", FSYM_PLANETS_JACOBI, N, M0, m, G, 0.0, &rw3, &lrw3, &iw3, &liw3))
        return fail("setup A");
    memcpy(x, y, sizeof x);
    st = fsym_planets_step(N, M0, m, G, &y[0][0], &w[0][0], H, 5, field, f, 0.0, rw3, lrw3,
                           iw3, liw3);
    if (st != FSYM_ERR_NO_GRADIENT || memcmp(x, y, sizeof x)) return fail("gradient refused");

    /* a close encounter: two planets 0.1 apart, within 3 mutual Hill radii */
    double m2[2] = {1.0e-3, 1.0e-3}, q[2][3] = {{1.0, 0.0, 0.0}, {1.1, 0.0, 0.0}};
    double p[2][3] = {{0.0, 1.0, 0.0}, {0.0, 0.95, 0.0}}, q0[2][3], p0[2][3];
    double *rw4;
    int *iw4, lrw4, liw4;
    memcpy(q0, q, sizeof q); memcpy(p0, p, sizeof p);
    if (setup("T2", FSYM_PLANETS_DEMOCRATIC, 2, 1.0, m2, 1.0, 3.0, &rw4, &lrw4, &iw4, &liw4))
        return fail("setup encounter");
    st = fsym_planets_step(2, 1.0, m2, 1.0, &q[0][0], &p[0][0], 0.01, 5, NULL, NULL, 0.0, rw4,
                           lrw4, iw4, liw4);
    fsym_planets_message(st, rw4, lrw4, iw4, liw4, msg, (int)sizeof msg);
    if (st != FSYM_ERR_ENCOUNTER || memcmp(q, q0, sizeof q) || memcmp(p, p0, sizeof p) ||
        !strstr(msg, "bodies 1 and 2") || iw4[8] != 1 || iw4[9] != 2)
        return fail(msg);

    /* a corrected method (lazy kernel + corrector 17, Kepler masses eta_k): 40 + 23 steps
     * bitwise 63, the sizes by the formula (nop 3, nslot 6), a restart from copies bitwise */
    double *rw5, *rw6, *ck5;
    int *iw5, *iw6, *ick5, lrw5, liw5;
    if (setup("WHK-L+C17", FSYM_PLANETS_JACOBI_ETA, N, M0, MS, G, 0.0, &rw5, &lrw5, &iw5,
              &liw5))
        return fail("setup WHK-L+C17");
    if (lrw5 != 30 + 13 * N + 2 * 3 + 3 * N * 6 || liw5 != 79 + 3) return fail("sizes WHK-L");
    memcpy(x, X0, sizeof x); memcpy(v, V0, sizeof v);
    st = fsym_planets_step(N, M0, MS, G, &x[0][0], &v[0][0], H, 40, NULL, NULL, 0.0, rw5, lrw5,
                           iw5, liw5);
    if (st != 0) return fail("WHK-L+C17 40 steps");
    ck5 = malloc(sizeof(double) * (size_t)lrw5); ick5 = malloc(sizeof(int) * (size_t)liw5);
    memcpy(ck5, rw5, sizeof(double) * (size_t)lrw5);
    memcpy(ick5, iw5, sizeof(int) * (size_t)liw5);
    st = fsym_planets_step(N, M0, MS, G, &x[0][0], &v[0][0], H, 23, NULL, NULL, 0.0, rw5, lrw5,
                           iw5, liw5);
    if (st != 0) return fail("WHK-L+C17 23 steps");
    if (setup("WHK-L+C17", FSYM_PLANETS_JACOBI_ETA, N, M0, MS, G, 0.0, &rw6, &lrw5, &iw6,
              &liw5))
        return fail("setup WHK-L+C17 2");
    memcpy(y, X0, sizeof y); memcpy(w, V0, sizeof w);
    st = fsym_planets_step(N, M0, MS, G, &y[0][0], &w[0][0], H, 63, NULL, NULL, 0.0, rw6, lrw5,
                           iw6, liw5);
    if (st != 0 || memcmp(x, y, sizeof x) || memcmp(v, w, sizeof v))
        return fail("WHK-L+C17 40 + 23");
    st = fsym_planets_state(N, &y[0][0], &w[0][0], ck5, lrw5, ick5, liw5);
    st = st ? st : fsym_planets_step(N, M0, MS, G, &y[0][0], &w[0][0], H, 23, NULL, NULL, 0.0,
                                     ck5, lrw5, ick5, liw5);
    if (st != 0 || memcmp(x, y, sizeof x) || memcmp(v, w, sizeof v))
        return fail("WHK-L+C17 restart");
    free(rw5); free(iw5); free(rw6); free(iw6); free(ck5); free(ick5);

    double e;
    if (fsym_planets_energy(N, M0, MS, G, &X0[0][0], &V0[0][0], &e) != 0 || !(e < 0.0))
        return fail("energy");
    printf("c_planets: all checks passed (%s)\n", msg);
    free(rw); free(iw); free(rw2); free(iw2); free(ck); free(ick); free(rw3); free(iw3);
    free(rw4); free(iw4);
    return 0;
}
