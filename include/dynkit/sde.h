/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/sde.h — noise: counter-based random numbers and stochastic differential equations.
 *
 * Random numbers come from Philox4x32-10 (Salmon, Moraes, Dror, Shaw, "Parallel random
 * numbers: as easy as 1, 2, 3", SC'11), a counter-based generator: each number is a
 * function of (seed, stream, counter) alone, so a run's noise is fixed by the seed and the
 * run's index (its stream) and is the same on any number of threads or MPI ranks.
 *
 * A model with noise (a model file's `wiener`, `normal(m, s)`, `ran(x)`) reads the current
 * values of its noise slots from its parameter struct; the solver writes them before each
 * evaluation. A Wiener slot holds dW/dt (a standard normal number divided by sqrt(dt) over
 * a step dt: XPPAUT's meaning, so `x' = f + s*w` with Euler is Euler–Maruyama), a normal
 * slot a standard normal number, a uniform slot a number uniform on [0, 1). The model's
 * formulas scale them (m + s*z, x*u).
 *
 * Methods (docs/solvers.md, "Noise"):
 *   DYN_SDE_EM    Euler–Maruyama with a fixed step: every slot drawn once per step (strong
 *                 order 1/2, weak order 1; strong order 1 for additive noise);
 *   DYN_SDE_MAP   a discrete map whose formulas draw noise (XPPAUT's meth=discrete);
 *   DYN_SDE_RKMIL the derivative-free Runge–Kutta Milstein scheme of Kloeden and Platen
 *                 (Numerical Solution of SDEs, 1992, eq. 11.1.5) for right-hand sides
 *                 affine in the Wiener slots with additive, scalar or diagonal (commuting)
 *                 noise: strong order 1, with adaptive steps by step doubling on one
 *                 Brownian path: every value of W drawn is kept, and a point between two
 *                 known ones comes from the Brownian bridge, so a rejected step changes
 *                 nothing of the path (Rackauckas and Nie, "Adaptive methods for stochastic
 *                 differential equations via natural embeddings and rejection sampling
 *                 with memory", 2017, with every point kept rather than a stack);
 *   DYN_SDE_SRIW1 Rößler's stochastic Runge–Kutta method SRIW1 ("Runge–Kutta methods for the
 *                 strong approximation of solutions of stochastic differential equations",
 *                 SIAM J. Numer. Anal. 48, 2010) for the same noise as rkmil: strong order
 *                 1.5, weak order 2, adaptive with the embedded error estimate of Rackauckas
 *                 and Nie on the same kept Brownian path, which here also carries the time
 *                 integral of W over each step (drawn with dW, split by the bridge of the
 *                 pair when a step is rejected); no events.
 *
 * Events (dyn_sde_opts.events; a model file's `global`): found and fired as dyn_solve does
 * (solve.h: sign changes of g, resets, XPPAUT's cascades, terminal events, Zeno runs), on
 * the scheme's own interpolant: the straight line between the states at the ends of a
 * fixed step (for Euler–Maruyama, the step with the Brownian increment at its mean given
 * the two ends), the broken line through the states at t, t + h/2 and t + h of an
 * adaptive step (its two half steps). The crossing is located on it (Brent's method); the
 * state there is the interpolant's. After a reset inside a step, the rest of the step
 * runs from the event on the same Brownian path: W at the event comes from the Brownian
 * bridge between the step's ends (a fixed step) or the path's known points (adaptive), so
 * the path stays a sample of Brownian motion and the seed still fixes the run; a normal or
 * uniform slot keeps its step's value.
 */
#ifndef DYNKIT_SDE_H
#define DYNKIT_SDE_H

#include <stddef.h>
#include <stdint.h>

#include "dynkit/ode.h"
#include "dynkit/solve.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Philox4x32 (Salmon et al., SC'11; Random123's philox4x32_R): rounds rounds (10 is the
 * standard) of the counter ctr under key, into out. out depends on (ctr, key) alone, so
 * any number can be computed directly, in any order, on any thread or machine. Checked
 * against Random123's known-answer vectors. */
void dyn_philox4x32(const uint32_t ctr[4], const uint32_t key[2], int rounds,
                    uint32_t out[4]);

/* A uniform number in (0, 1) from two words of a block: 53 random bits plus one half,
 * (((hi << 32 | lo) >> 11) + 1/2) 2^-53. */
double dyn_philox_unit(uint32_t hi, uint32_t lo);

/* The random numbers of one run: Philox4x32-10 with key (seed low, seed high) and counter
 * (block low, block high, stream low, 2^31 | stream high), block = 0, 1, 2, ... in the order
 * the numbers are asked for. The top bit of the last word keeps these counters apart from
 * those of a sweep's random run tables (dynkit/sweep.h), whose last word is 0. Each block
 * gives two standard normal numbers (Box–Muller, cos then sin) or two uniform ones. */
typedef struct dyn_rng {
    uint32_t key[2];
    uint32_t stream[2];
    uint64_t block;
    double spare;   /* the second normal of the last block */
    int has_spare;
} dyn_rng;

void dyn_rng_init(dyn_rng *r, uint64_t seed, uint64_t stream);
double dyn_rng_normal(dyn_rng *r);
double dyn_rng_uniform(dyn_rng *r); /* in [0, 1) */

/* A random number drawn once, when a model is prepared (a model file's table whose formula
 * calls ran() or normal(): XPPAUT computes such a table once, when it reads the file): the
 * kind-th (DYN_NOISE_UNIFORM: on [0, 1); DYN_NOISE_NORMAL: standard normal) number of
 * call site `call` at point k, from the Philox4x32-10 block with key (seed low, seed high)
 * and counter (k low, k high, call, 2^30), kept apart from the runs' counters (top bit
 * set) and a sweep's random run tables (last word 0). Fixed by the seed alone. */
double dyn_table_random(uint64_t seed, long call, long k, int kind);

/* Kinds of noise slot. */
typedef enum dyn_noise_kind {
    DYN_NOISE_WIENER = 0,  /* dW/dt over the step: z / sqrt(dt) */
    DYN_NOISE_NORMAL = 1,  /* standard normal z, drawn once per step */
    DYN_NOISE_UNIFORM = 2  /* uniform on [0, 1), drawn once per step */
} dyn_noise_kind;

/* What the right-hand side does with its noise, as the translator proves it from the
 * formulas (dyn_model.noise_class): which methods can integrate it. */
typedef enum dyn_noise_class {
    DYN_NOISE_GENERAL = 0,     /* only Euler–Maruyama: a right-hand side not affine in the
                                * Wiener slots, or normal()/ran() slots */
    DYN_NOISE_ADDITIVE = 1,    /* affine in the Wiener slots with coefficients that do not
                                * depend on the state */
    DYN_NOISE_COMMUTATIVE = 2  /* affine, and no Wiener slot's coefficient depends on a state
                                * that another Wiener slot moves (scalar or diagonal noise):
                                * Milstein's correction needs no Lévy areas */
} dyn_noise_class;

/* Jumps at the start of each step (a model file's Markov states, XPPAUT's `markov`): called
 * by the fixed-step methods (EM, MAP) at (t, y) with the step's length h and its noise slots
 * already written, before the step's evaluation; it may change states of y in place (the
 * step then starts from the new values). 0, or non-zero to stop the run. */
typedef int (*dyn_jump_fn)(double t, double h, double *y, void *par);

/* A system with noise: sys.f reads the n_noise slots at noise (inside sys.par), which the
 * solver writes before each evaluation; kinds[j] is the dyn_noise_kind of slot j. */
typedef struct dyn_sde {
    dyn_system sys;
    int n_noise;
    const int *kinds;
    double *noise;
    dyn_noise_class noise_class;
} dyn_sde;

/* One step of h of a Markov chain of n states (XPPAUT's `markov`, its transition rule): the
 * chain's value *z is state i when |*z - i| < 1e-4 (i = 0 .. n-1; any other value is left
 * as it is, as XPPAUT leaves it), rates is the n x n matrix of transition rates row by row
 * (from i to j at rates[i n + j]; the diagonal is not read), u uniform on [0, 1). The chain
 * goes to the first j != i, in order, with u < h * (the sum of row i's rates up to j), else
 * stays: the probability of i -> j over the step is h * rate(i, j) (first order in h, as
 * long as h times the row's sum stays below 1). Returns 0, or -1 when a rate of row i is
 * negative or not finite (*z is then left as it was). */
int dyn_markov_step(double *z, int n, const double *rates, double h, double u);

/* One reaction of Gillespie's direct method (XPPAUT's `special z=gill(0, r1, ..., rm)`):
 * from the m reaction rates and two numbers u1, u2 uniform on [0, 1), out[0] is the waiting
 * time -log(1 - u1)/R (R the rates' sum) and out[1 + k] is 1 for the reaction k whose share
 * of R holds u2 R (the first k with u2 R < r_0 + ... + r_k), 0 for the others. All rates 0
 * (an absorbing state): out[0] = 0 and no reaction. Returns 0, or -1 when a rate is negative
 * or not finite (out all NaN). */
int dyn_gillespie_step(double *out, int m, const double *rates, double u1, double u2);

typedef enum dyn_sde_method {
    DYN_SDE_EM = 0,
    DYN_SDE_RKMIL = 1,
    DYN_SDE_MAP = 2,  /* a discrete map with noise: every slot drawn once per step, then
                       * y_{k+1} = f(t_k, y_k) (XPPAUT's meth=discrete; a Wiener slot is z /
                       * sqrt(h), z for the map's step 1) */
    DYN_SDE_SRIW1 = 3 /* SRIW1: per step and noise two normals, z1 for dW = sqrt(h) z1 and z2
                       * for the time integral I_(1,0) = (h dW + sqrt(h^3/3) z2) / 2 */
} dyn_sde_method;

typedef struct dyn_sde_opts {
    double h;              /* EM and fixed rkmil/sriw1: the step; adaptive rkmil/sriw1: the
                            * first step (0: 1e-3 of the span) */
    int fixed;             /* rkmil, sriw1: 1 takes fixed steps h (no error control) */
    double rtol, atol;     /* adaptive rkmil/sriw1 (0: 1e-3 and 1e-6) */
    double max_step;       /* adaptive: 0 = the span */
    long max_steps;        /* adaptive: 0 = 10^7; fixed steps: 0 = no limit, else a longer
                            * grid is refused before the first step */
    double out_step;       /* adaptive: samples at t0 + k out_step (steps land on
                            * them); 0 = a sample at every accepted step */
    dyn_end_policy end;    /* fixed steps: as dyn_fixed_solve */
    long every;            /* fixed steps: keep every K-th sample (and the last) */
    uint64_t seed, stream; /* the noise: dyn_rng_init(seed, stream) */
    /* events (dyn_event, ode.h) as dyn_solve fires them (solve.h: reports, resets,
     * cascades, terminal events, Zeno runs): see "Events" above; not for DYN_SDE_MAP or
     * DYN_SDE_SRIW1 */
    const dyn_event *events;
    int n_events;
    dyn_event_fn on_event; /* may be NULL */
    void *event_ctx;
    int xppaut_globals;    /* 1: instants and cascades by XPPAUT's rules (solve.h) */
    dyn_jump_fn jump;      /* the system's jumps (Markov states) at each fixed step's start,
                            * with sys.par; NULL: none; not for rkmil */
    dyn_output_fn output;
    void *output_ctx;
    dyn_progress_fn progress;
    void *progress_ctx;
} dyn_sde_opts;

/* Points of the Brownian path an adaptive run keeps ahead of its time at most; a run that
 * needs more stops with DYN_ERR_CAPACITY. */
#define DYN_SDE_MAX_POINTS 256

/* Doubles of workspace dyn_sde_solve needs for n states, n_noise slots and n_events
 * events. */
size_t dyn_sde_work_size(int n, int n_noise, int n_events);

/* Integrate sde from (t0, y0) to t1 with method; y (n) receives the last good state. Samples
 * stream through opts->output (sample 0 at t0). Never allocates. Returns res->status:
 * DYN_ERR_ARG (with the reason) when the method cannot integrate this noise. */
int dyn_sde_solve(dyn_sde_method method, const dyn_sde *sde, double t0, double t1,
                  const double *y0, double *y, double *work, const dyn_sde_opts *opts,
                  dyn_result *res);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_SDE_H */
