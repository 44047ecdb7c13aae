/* Randomised bad input through the C face of forward-symplectic, built with the library
 * under AddressSanitizer (test/fuzz/CMakeLists.txt). Every case runs in a forked child, so
 * that a crash or a sanitizer report is counted instead of ending the run; the parent checks
 * each child's verdict. Per case it asserts: the call returns, the status is a known code,
 * a bad input gets a non-zero status, q and v are bitwise unchanged on failure, the message
 * is non-empty and printable; ASan reports any out-of-bounds access or leak-free misuse.
 *
 * usage: fuzz_capi [cases per class (default 200)] [seed] [report file]
 * The report gets one line per class: `c-asan CLASS cases clear intact violations crashes`.
 * Exit status 0 only when every case passed and no child crashed.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fsym.h"

/* A sanitizer report ends a child with 99 (not 1..7, the verdicts). */
const char *__asan_default_options(void) { return "exitcode=99:detect_leaks=0"; }

static uint64_t seed = 20261123u;

static uint64_t next(void)
{
    seed ^= seed >> 12;
    seed ^= seed << 25;
    seed ^= seed >> 27;
    return (seed * 2685821657736338717ull) >> 1;
}

static int pick(int lo, int hi) { return lo + (int)(next() % (uint64_t)(hi - lo + 1)); }

static double wild(void)
{
    switch (pick(0, 9)) {
    case 0: return NAN;
    case 1: return INFINITY;
    case 2: return -INFINITY;
    case 3: return 1.7976931348623157e308;
    case 4: return 0.0;
    default: return (double)pick(-2000, 2000) / 1000.0;
    }
}

static int kepler(int d, int n, const double *q, double *a, void *user)
{
    (void)user;
    for (int j = 0; j < n; ++j) {
        double r2 = 0.0;
        for (int k = 0; k < d; ++k) r2 += q[j * d + k] * q[j * d + k];
        double f = -1.0 / (r2 * sqrt(r2));
        for (int k = 0; k < d; ++k) a[j * d + k] = f * q[j * d + k];
    }
    return 0;
}

static int failing(int d, int n, const double *q, double *a, void *user)
{
    int *count = (int *)user;
    kepler(d, n, q, a, NULL);
    return ++*count == 3 ? 7 : 0;
}

static int printable(const char *s)
{
    if (s[0] == '\0') return 0;
    for (; *s; ++s)
        if ((unsigned char)*s < 32 || (unsigned char)*s > 126) return 0;
    return 1;
}

static int same(const double *a, const double *b, int m) { return memcmp(a, b, m * sizeof *a) == 0; }

/* A random label: catalogue names, parametrised ones, raw bytes, long strings. */
static void random_label(char *buf, size_t cap)
{
    static const char *names[] = {"FR", "A", "A'", "C", "C'", "A6", "BM", "M2(-0.5)",
                                  "GFR5(0.3)", "T2", "SRKN6b", "a prime", "m2(-1/2)"};
    size_t n;
    switch (pick(0, 5)) {
    case 0: snprintf(buf, cap, "%s", names[pick(0, 12)]); break;
    case 1: snprintf(buf, cap, "A%d", pick(-5, 999)); break;
    case 2: snprintf(buf, cap, "M2(%g)", wild() * pow(10.0, pick(-5, 300))); break;
    case 3:
        n = (size_t)pick(0, 40);
        for (size_t k = 0; k < n && k + 1 < cap; ++k) buf[k] = (char)pick(1, 255);
        buf[n < cap ? n : cap - 1] = '\0';
        break;
    case 4:
        n = (size_t)pick(60, (int)cap - 1);
        memset(buf, 'A', n);
        buf[n] = '\0';
        break;
    default: snprintf(buf, cap, "FR%*s", pick(0, 300), "x"); break;
    }
}

/* One case of a class; returns a verdict bit set: 1 unclear status, 2 state changed,
 * 4 bad message. */
static int one_case(int klass)
{
    char label[512], msg[256];
    double q[2], v[2], q0[2], v0[2];
    fsym_integrator *h = NULL;
    int st, verdict = 0, count = 0;
    long long nf, last;
    random_label(label, sizeof label);
    switch (klass) {
    case 0: /* labels and NULLs at creation */
        switch (pick(0, 4)) {
        case 0: st = fsym_create(NULL, 2, 1, kepler, NULL, NULL, &h); break;
        case 1: st = fsym_create(label, 2, 1, NULL, NULL, NULL, &h); break;
        case 2: st = fsym_create(label, 2, 1, kepler, NULL, NULL, NULL); break;
        default: st = fsym_create(label, pick(-1, 3), pick(-1, 2), kepler, NULL, NULL, &h);
        }
        if (st < 0 || st > FSYM_ERR_LAST || (st != 0 && h != NULL)) verdict |= 1;
        fsym_status_message(st, msg, (int)sizeof msg);
        if (st != 0 && !printable(msg)) verdict |= 4;
        fsym_destroy(h);
        break;
    case 1: /* steps: NaN/Inf, bad h and counts, NULL arrays, failing callback */
        st = fsym_create(pick(0, 1) ? "C'" : "FR", 2, 1, pick(0, 3) ? kepler : failing, NULL,
                         &count, &h);
        if (st != 0) return 1;
        q[0] = 10.0; q[1] = 0.0; v[0] = 0.0; v[1] = 0.1;
        if (pick(0, 3) == 0) q[pick(0, 1)] = wild();
        if (pick(0, 3) == 0) v[pick(0, 1)] = wild();
        memcpy(q0, q, sizeof q); memcpy(v0, v, sizeof v);
        {
            double hs = pick(0, 3) ? 0.01 : wild();
            int nstep = pick(0, 5) ? pick(1, 5) : pick(-3, 0);
            int bad = !isfinite(q[0]) || !isfinite(q[1]) || !isfinite(v[0]) || !isfinite(v[1])
                      || !isfinite(hs) || hs == 0.0 || nstep < 1;
            switch (pick(0, 5)) {
            case 0: st = fsym_step(h, NULL, v, hs, nstep); bad = 1; break;
            case 1: st = fsym_step(h, q, NULL, hs, nstep); bad = 1; break;
            default: st = fsym_step(h, q, v, hs, nstep);
            }
            if (st < 0 || st > FSYM_ERR_LAST || (bad && st == 0)) verdict |= 1;
            if (bad && !(same(q, q0, 2) && same(v, v0, 2))) verdict |= 2;
            if (st != 0) {
                if (fsym_last_message(h, msg, (int)sizeof msg) != 0 || !printable(msg))
                    verdict |= 4;
                if (fsym_steps_done(h, &last, NULL) != 0 || last < 0) verdict |= 1;
            }
        }
        fsym_counts(h, &nf, NULL);
        fsym_counts(h, NULL, NULL);
        fsym_steps_done(h, NULL, NULL);
        fsym_last_message(h, NULL, 10);
        fsym_destroy(h);
        break;
    case 2: /* NULL handles and buffers everywhere, tiny buffers */
        if (fsym_step(NULL, q, v, 0.1, 1) != FSYM_ERR_NOT_INITIALIZED) verdict |= 1;
        if (fsym_counts(NULL, &nf, &nf) != FSYM_ERR_NOT_INITIALIZED) verdict |= 1;
        if (fsym_steps_done(NULL, &last, &last) == 0) verdict |= 1;
        if (fsym_last_message(NULL, msg, 10) == 0) verdict |= 1;
        if (fsym_reset_cache(NULL) == 0) verdict |= 1;
        if (fsym_checkpoint_length(NULL, &nf) == 0) verdict |= 1;
        fsym_status_message(pick(-5, 40), NULL, 10);
        {
            int len = pick(-2, 3);
            char small[4] = {'x', 'x', 'x', 'x'};
            fsym_status_message(pick(-5, 40), small, len);
            if (len >= 1 && small[len - 1] != '\0') verdict |= 4;
            if (len < 4 && len >= 0 && small[3] != 'x') verdict |= 2;
        }
        fsym_destroy(NULL);
        break;
    default: /* checkpoints: corrupt, short, NULL */
        st = fsym_create("A'", 2, 1, kepler, NULL, NULL, &h);
        if (st != 0) return 1;
        q[0] = 10.0; q[1] = 0.0; v[0] = 0.0; v[1] = 0.1;
        fsym_step(h, q, v, 0.01, 5);
        {
            long long m = 0;
            fsym_checkpoint_length(h, &m);
            double *ck = malloc((size_t)m * sizeof *ck);
            fsym_checkpoint_save(h, q, v, ck, m);
            for (int k = pick(1, 3); k > 0; --k) ck[pick(0, (int)m - 1)] = wild();
            long long len = pick(0, 4) ? m : pick(0, (int)m);
            memcpy(q0, q, sizeof q); memcpy(v0, v, sizeof v);
            st = fsym_checkpoint_load(h, q, v, pick(0, 9) ? ck : NULL, len);
            if (st != 0 && st != FSYM_ERR_CHECKPOINT && st != FSYM_ERR_BAD_ARGUMENT) verdict |= 1;
            if (st != 0 && !(same(q, q0, 2) && same(v, v0, 2))) verdict |= 2;
            free(ck);
        }
        fsym_destroy(h);
    }
    return verdict;
}

int main(int argc, char **argv)
{
    static const char *classes[] = {"create-labels", "steps", "null-handles", "checkpoint"};
    int ncases = argc > 1 ? atoi(argv[1]) : 200;
    FILE *report = argc > 3 ? fopen(argv[3], "a") : NULL;
    int failed = 0;
    if (argc > 2) seed = strtoull(argv[2], NULL, 10) | 1u;
    /* the header lists every code the library returns, and no more */
    for (int code = 0; code <= FSYM_ERR_LAST + 1; ++code) {
        char text[128];
        fsym_status_message(code, text, (int)sizeof text);
        if ((strcmp(text, "unknown status code") == 0) != (code == FSYM_ERR_LAST + 1)) {
            printf("fsym.h and the library disagree on status code %d: \"%s\"\n", code, text);
            ++failed;
        }
    }
    for (int klass = 0; klass < 4; ++klass) {
        int clear = 0, intact = 0, printed = 0, crashes = 0, bad = 0;
        for (int c = 0; c < ncases; ++c) {
            uint64_t child_seed = next();
            fflush(NULL);
            pid_t pid = fork();
            if (pid == 0) {
                seed = child_seed | 1u;
                _exit(one_case(klass));
            }
            int status = 0;
            waitpid(pid, &status, 0);
            if (!WIFEXITED(status) || WEXITSTATUS(status) > 7) {
                ++crashes; ++bad;
                continue;
            }
            int verdict = WEXITSTATUS(status);
            if (!(verdict & 1)) ++clear;
            if (!(verdict & 2)) ++intact;
            if (!(verdict & 4)) ++printed;
            if (verdict) ++bad;
        }
        printf("c-asan %-14s cases %d clear %d intact %d printable %d crashes %d\n",
               classes[klass], ncases, clear, intact, printed, crashes);
        if (report)
            fprintf(report, "c-asan %s %d %d %d %d %d\n", classes[klass], ncases, clear, intact,
                    bad, crashes);
        failed += bad;
    }
    if (report) fclose(report);
    return failed ? 1 : 0;
}
