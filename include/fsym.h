/* forward-symplectic: C interface (hand-written; see src/fsym_capi.f90).
 *
 * Every function returns an integer status (0 = success; codes as in src/fsym_status.f90,
 * text from fsym_status_message). Nothing in the library ever ends the program.
 * Arrays are C arrays double q[n][d] (Fortran q(d, n)): body j, component k is q[j][k].
 * Link with -lfsym -lgfortran (or through pkg-config fsym / CMake forward-symplectic::fsym).
 */
#ifndef FSYM_H
#define FSYM_H

#ifdef __cplusplus
extern "C" {
#endif

enum {
    FSYM_SUCCESS = 0,
    FSYM_ERR_UNKNOWN_METHOD = 1,
    FSYM_ERR_BAD_PARAMETER = 2,
    FSYM_ERR_INCONSISTENT_SCHEME = 3,
    FSYM_ERR_BAD_STEP = 4,
    FSYM_ERR_NONFINITE_STATE = 5,
    FSYM_ERR_NONFINITE_FORCE = 6,
    FSYM_ERR_SHAPE = 7,
    FSYM_ERR_NO_GRADIENT = 8,
    FSYM_ERR_NOT_INITIALIZED = 9,
    FSYM_ERR_WORK_SIZE = 10,
    FSYM_ERR_MODEL = 11,
    FSYM_ERR_NOT_ELLIPTIC = 12,
    FSYM_ERR_NO_CONVERGENCE = 13,
    FSYM_ERR_IO = 14,
    FSYM_ERR_CAPACITY = 15,
    FSYM_ERR_NO_POTENTIAL = 16,
    FSYM_ERR_BAD_REQUEST = 17,
    FSYM_ERR_LAPACK = 18,
    FSYM_ERR_BAD_ARGUMENT = 19,      /* NULL pointer, nstep <= 0, label too long */
    FSYM_ERR_STEP_TOO_LARGE = 20,    /* refused by the step-size guard */
    FSYM_ERR_CHECKPOINT = 21,        /* checkpoint corrupt, other version, or not fitting */
    FSYM_ERR_CONVENTION = 22,        /* F77 caller with non-default integer size */
    FSYM_ERR_NO_MEMORY = 23,         /* an allocation failed (e.g. a huge method table) */
    FSYM_ERR_BUSY = 24,              /* integrator called from its own callback */
    FSYM_ERR_ENCOUNTER = 25,         /* close encounter: step undone, the pair named */
    FSYM_ERR_LAST = 25               /* largest code in use */
};

/* Longest method label accepted (longer ones: FSYM_ERR_BAD_ARGUMENT, never cut). */
#define FSYM_NAME_MAX 256

/* Opaque integrator. */
typedef struct fsym_integrator fsym_integrator;

/* Accelerations a[n][d] at positions q[n][d]; return non-zero to report a failure
 * (the step is then undone and fsym_step returns FSYM_ERR_MODEL). */
typedef int (*fsym_accel_fn)(int d, int n, const double *q, double *a, void *user);

/* Gradient term g_j = (1/m_j) d/dq_j sum_i m_i |a_i|^2 at q, given a = a(q). */
typedef int (*fsym_grad_fn)(int d, int n, const double *q, const double *a, double *g,
                            void *user);

/* A new integrator for the method label ("FR", "A", "A'", "C", "A6", "BM", "M2(-0.5)", ...)
 * on arrays of d components and n bodies. grad may be NULL: methods with a gradient kick
 * (A, C, AN) then need their primed (extrapolated) form. *handle is NULL on failure.
 * NULL method, accel or handle: FSYM_ERR_BAD_ARGUMENT. */
int fsym_create(const char *method, int d, int n, fsym_accel_fn accel, fsym_grad_fn grad,
                void *user, fsym_integrator **handle);

/* nstep steps of size h; on failure q, v hold the state after the last completed step
 * (fsym_steps_done says how many, fsym_last_message why). nstep <= 0, NULL q or v:
 * FSYM_ERR_BAD_ARGUMENT; NULL handle: FSYM_ERR_NOT_INITIALIZED. */
int fsym_step(fsym_integrator *handle, double *q, double *v, double h, int nstep);

/* Observer: called with the state (double[n][d]), the time and the step count since
 * creation; a non-zero return stops the run there (the call then returns success). */
typedef int (*fsym_observe_fn)(int d, int n, const double *q, const double *v, double t,
                               long long step, void *user);

/* Whole steps of h from the integrator's time towards t_end, then one shorter step that
 * lands on t_end exactly; h must point from the time to t_end (else FSYM_ERR_BAD_STEP).
 * On failure q, v hold the state after the last completed step. */
int fsym_run_to(fsym_integrator *handle, double *q, double *v, double h, double t_end);

/* The integrator's time (t0 + the steps taken, without accumulated round-off). */
int fsym_time(const fsym_integrator *handle, double *t);

/* From now on fsym_step and fsym_run_to call observe every `every` (>= 1) steps;
 * observe = NULL removes it. every < 1: FSYM_ERR_BAD_ARGUMENT. */
int fsym_set_observer(fsym_integrator *handle, fsym_observe_fn observe, int every,
                      void *user);

/* Steps completed by the last fsym_step call (*last) and since creation (*total);
 * either pointer may be NULL. */
int fsym_steps_done(const fsym_integrator *handle, long long *last, long long *total);

/* The full message of the last failing call on this integrator (method, step, stage,
 * cause), NUL-terminated in buf of len bytes; empty when nothing failed. */
int fsym_last_message(const fsym_integrator *handle, char *buf, int len);

/* Forget the cached force: call it after changing what the callbacks read (a mass, a
 * coupling) between steps. */
int fsym_reset_cache(fsym_integrator *handle);

/* Checkpoint and restart: the complete state (q, v, clock, counters, method, cached forces,
 * compensation terms) as one array of doubles with a version tag, the same format on every
 * face. A run resumed with fsym_checkpoint_load (on an integrator created for the same
 * method and arrays, with the callbacks' data in the same state) is bitwise identical to an
 * uninterrupted one. Errors: FSYM_ERR_CHECKPOINT (corrupt, other version/method/shape). */
int fsym_checkpoint_length(const fsym_integrator *handle, long long *len);
int fsym_checkpoint_save(fsym_integrator *handle, const double *q, const double *v,
                         double *ck, long long len);
int fsym_checkpoint_load(fsym_integrator *handle, double *q, double *v, const double *ck,
                         long long len);

/* Force and gradient evaluations so far (a NULL pointer is skipped). */
int fsym_counts(const fsym_integrator *handle, long long *nforce, long long *ngrad);

/* Largest local omega^2 at q (e.g. 2 G (m_i + m_j) / r_ij^3 over the pairs) and the
 * distance r where it occurs; return non-zero to report a failure. */
typedef int (*fsym_freq_fn)(int d, int n, const double *q, double *omega2, double *r,
                            void *user);

/* The step-size guard: every step is checked at its start, at every drift (end point and
 * chord) and at its end against fraction * x* (x*: the method's stability limit; fraction
 * <= 0 means 1); a step beyond it is refused with FSYM_ERR_STEP_TOO_LARGE and q, v of the
 * last step taken. freq NULL turns the guard off. */
int fsym_set_guard(fsym_integrator *handle, fsym_freq_fn freq, double fraction);

/* Calls from inside a callback on the integrator that called it (fsym_step,
 * checkpoints) are refused with FSYM_ERR_BUSY; q and v that share memory with
 * FSYM_ERR_BAD_ARGUMENT. */

/* Free the integrator (NULL is ignored; ignored from inside its own callback; a handle
 * already destroyed is ignored while its memory is not reused, but set it to NULL). */
void fsym_destroy(fsym_integrator *handle);

/* NUL-terminated text of a status code in buf (at most len bytes). */
void fsym_status_message(int code, char *buf, int len);

/* ---- The planetary drop-in (doc/legacy.md; the F77 routines FSYMPW ... FSYMPE) ----------
 * A heliocentric legacy code's state: central mass m0, masses m[n] (massive first, then
 * test particles of mass 0), G, heliocentric x[n][3], v[n][3]. The state of the run lives in
 * the caller's work arrays double rw[lrw], int iw[liw] (no global state: reentrant; rw and iw
 * are a checkpoint). lrw = 30 + 13 n + 2 nop + 3 n nslot, liw = 79 + nop (nop stages of the
 * kernel, 3 with a corrector; nslot = 4, + 1 with gradient kicks, + 2 with extrapolated kicks),
 * or ask fsym_planets_work_size. Processed labels ("WHK-L+C17", "WH+C17", "WHK-M+C17",
 * "T2+C5": a kernel with a symplectic corrector applied at output only) are accepted. */

/* Extra accelerations a[n][3] at the heliocentric positions x[n][3] (a J2, a post-Newtonian
 * term, a disk); return non-zero to report a failure (the step is undone, FSYM_ERR_MODEL). */
typedef int (*fsym_planets_force_fn)(int n, const double *x, double *a, void *user);

/* Coordinates: Jacobi (Kepler masses m0 eta_k / eta_(k-1)), democratic heliocentric, Jacobi
 * with the Kepler masses eta_k (PLANETS_KEPLER_ETA, REBOUND's WHFast choice). */
enum { FSYM_PLANETS_JACOBI = 1, FSYM_PLANETS_DEMOCRATIC = 2, FSYM_PLANETS_JACOBI_ETA = 3 };

/* Work sizes of the method label for n bodies besides the centre. */
int fsym_planets_work_size(const char *method, int n, int *lrw, int *liw);

/* Set up rw, iw: method label, coordinates (FSYM_PLANETS_JACOBI, _DEMOCRATIC, _JACOBI_ETA), G,
 * masses, close-encounter radius hill in mutual Hill radii (0: off). On error nothing is
 * written. */
int fsym_planets_init(const char *method, int coords, int n, double m0, const double *m,
                      double g, double hill, double *rw, int lrw, int *iw, int liw);

/* nstep steps of size h of the heliocentric x, v. m0, m, G must be bitwise those of the
 * set-up (FSYM_ERR_CHECKPOINT otherwise). force may be NULL; fraction > 0 turns the step-size
 * guard on. FSYM_ERR_ENCOUNTER: a close encounter, the pair in iw[8], iw[9]. On failure x, v
 * hold the state after the iw[6] steps completed (unchanged when none was). */
int fsym_planets_step(int n, double m0, const double *m, double g, double *x, double *v,
                      double h, int nstep, fsym_planets_force_fn force, void *user,
                      double fraction, double *rw, int lrw, int *iw, int liw);

/* The heliocentric state kept in rw (the x, v the last step call returned): after restoring
 * rw and iw from a checkpoint, the state to go on from, bitwise. */
int fsym_planets_state(int n, double *x, double *v, const double *rw, int lrw, const int *iw,
                       int liw);

/* The message of the status the last call on rw, iw returned (the pair of an encounter, the
 * body whose mass differs, the steps completed), NUL-terminated in buf. */
int fsym_planets_message(int status, const double *rw, int lrw, const int *iw, int liw,
                         char *buf, int len);

/* Total energy (barycentric kinetic + potential) of a heliocentric state. */
int fsym_planets_energy(int n, double m0, const double *m, double g, const double *x,
                        const double *v, double *e);

#ifdef __cplusplus
}
#endif

#endif /* FSYM_H */
