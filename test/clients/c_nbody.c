/* C client of forward-symplectic through include/fsym.h: the outer solar system with its
 * own arrays and force callbacks (masses travel in the void *user pointer). Prints the final
 * state of each method for comparison with the modern API.
 * Build: cc -ffp-contract=off c_nbody.c $(pkg-config --cflags --libs --static fsym) */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "fsym.h"

#define NB 6

typedef struct { double gm[NB]; double g; double eps; long calls; } bodies;

/* accelerations by direct summation over pairs i < j */
static int accel(int d, int n, const double *q, double *a, void *user)
{
    bodies *b = (bodies *)user;
    const double e2 = b->eps * b->eps;
    if (d != 3) return 1;
    memset(a, 0, sizeof(double) * 3 * (size_t)n);
    for (int i = 0; i < n - 1; i++) {
        for (int j = i + 1; j < n; j++) {
            double dx = q[3 * j] - q[3 * i];
            double dy = q[3 * j + 1] - q[3 * i + 1];
            double dz = q[3 * j + 2] - q[3 * i + 2];
            double r2 = dx * dx + dy * dy + dz * dz + e2;
            double f = b->g / (r2 * sqrt(r2));
            a[3 * i] = a[3 * i] + b->gm[j] * f * dx;
            a[3 * i + 1] = a[3 * i + 1] + b->gm[j] * f * dy;
            a[3 * i + 2] = a[3 * i + 2] + b->gm[j] * f * dz;
            a[3 * j] = a[3 * j] - b->gm[i] * f * dx;
            a[3 * j + 1] = a[3 * j + 1] - b->gm[i] * f * dy;
            a[3 * j + 2] = a[3 * j + 2] - b->gm[i] * f * dz;
        }
    }
    b->calls++;
    return 0;
}

/* gradient term g_j = (1/m_j) d/dq_j sum_i m_i |a_i|^2, given a = a(q) */
static int grad(int d, int n, const double *q, const double *a, double *g, void *user)
{
    bodies *b = (bodies *)user;
    if (d != 3) return 1;
    memset(g, 0, sizeof(double) * 3 * (size_t)n);
    for (int i = 0; i < n - 1; i++) {
        for (int j = i + 1; j < n; j++) {
            double y[3], da[3];
            for (int k = 0; k < 3; k++) {
                y[k] = q[3 * j + k] - q[3 * i + k];
                da[k] = a[3 * i + k] - a[3 * j + k];
            }
            double r2 = y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + b->eps * b->eps;
            double rinv2 = 1.0 / r2;
            double f = b->g * rinv2 / sqrt(r2);
            double xda = y[0] * da[0] + y[1] * da[1] + y[2] * da[2];
            for (int k = 0; k < 3; k++) {
                double w = f * (da[k] - (3.0 * xda * rinv2) * y[k]);
                g[3 * j + k] = g[3 * j + k] + (2.0 * b->gm[i]) * w;
                g[3 * i + k] = g[3 * i + k] - (2.0 * b->gm[j]) * w;
            }
        }
    }
    return 0;
}

int main(void)
{
    static const double q0[NB][3] = {
        {-3.5023653, -3.8169847, -1.5507963}, {9.0755314, -3.0458353, -1.6483708},
        {8.3101420, -16.2901086, -7.2521278}, {11.4707666, -25.7294829, -10.8169456},
        {-15.5387357, -25.2225594, -3.1902382}, {0.0, 0.0, 0.0}};
    static const double v0[NB][3] = {
        {0.00565429, -0.00412490, -0.00190589}, {0.00168318, 0.00483525, 0.00192462},
        {0.00354178, 0.00137102, 0.00055029}, {0.00288930, 0.00114527, 0.00039677},
        {0.00276725, -0.00170702, -0.00136504}, {0.0, 0.0, 0.0}};
    const char *names[] = {"FR", "A", "A'", "C", "A6", "BM"};
    bodies b = {{0.000954786104043, 0.000285583733151, 0.0000437273164546,
                 0.0000517759138449, 7.692307692307693e-09, 1.00000597682},
                2.95912208286e-4, 0.0, 0};
    double q[NB][3], v[NB][3];
    char msg[64];
    fsym_integrator *h = NULL;
    int st;

    /* errors come back as a status, never as an exit */
    st = fsym_create("no such method", 3, NB, accel, NULL, &b, &h);
    fsym_status_message(st, msg, (int)sizeof msg);
    printf("unknown method: status %d (%s), handle %s\n", st, msg, h ? "set" : "NULL");
    if (st == 0 || h != NULL) return 1;

    for (int m = 0; m < 6; m++) {
        long long nf, ng;
        memcpy(q, q0, sizeof q);
        memcpy(v, v0, sizeof v);
        b.calls = 0;
        st = fsym_create(names[m], 3, NB, accel, grad, &b, &h);
        if (st != 0) { fprintf(stderr, "fsym_create %s: %d\n", names[m], st); return 2; }
        st = fsym_step(h, &q[0][0], &v[0][0], 10.0, 1000);
        if (st != 0) { fprintf(stderr, "fsym_step %s: %d\n", names[m], st); return 3; }
        fsym_counts(h, &nf, &ng);
        fsym_destroy(h);
        for (int j = 0; j < NB; j++)
            printf("c %s %2d %.17e %.17e %.17e %.17e %.17e %.17e\n", names[m], j + 1,
                   q[j][0], q[j][1], q[j][2], v[j][0], v[j][1], v[j][2]);
        printf("c %s counts %lld %lld\n", names[m], nf, ng);
        if (nf != b.calls) return 4;
    }
    return 0;
}
