/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/model.h — models: named states, parameters and outputs around a right-hand side.
 *
 * A model describes a system for people and tools: names, units and defaults of its states
 * and parameters, the right-hand side, extra outputs computed at each sample (energy,
 * constraint forces, ...), and its default run (time span, step, method, where an adaptive
 * method writes its samples). The CLI and the
 * report use built-in models only through this interface, so a user's own model in C gets
 * the same treatment (see examples/).
 *
 * Parameters live in a model-specific struct (par_size bytes); each dyn_param names one
 * double member by offset, so parameters can be set by name. The right-hand side receives a
 * pointer to that struct as its par argument.
 */
#ifndef DYNKIT_MODEL_H
#define DYNKIT_MODEL_H

#include <stddef.h>

#include "dynkit/ode.h"
#include "dynkit/sde.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DYN_PI 3.14159265358979323846

/* The default run of a model that names no method or no tolerances, whatever kind of model
 * it is (built in, a C model, a model file): an adaptive method at tolerances that keep a
 * long run right. dyn_solve's own defaults (DYN_DEFAULT_RTOL 1e-3, as MATLAB's ode45) leave
 * errors of a percent after a few periods of an oscillator. */
#define DYN_MODEL_METHOD "dp45"
#define DYN_MODEL_RTOL 1e-6
#define DYN_MODEL_ATOL 1e-9

/* Where a default run of an adaptive method writes its samples (dyn_model.samples). */
typedef enum dyn_sample_policy {
    DYN_SAMPLES_GRID = 0, /* the grid t0 + k*step (the seed's [0:Ts:endtime]) */
    DYN_SAMPLES_STEPS = 1 /* every accepted step: the steps follow the solution, e.g. across
                           * the decades of time of a stiff chemical transient */
} dyn_sample_policy;

/* A named quantity: a state or an extra output. */
typedef struct dyn_var {
    const char *name;
    const char *unit;        /* SI unit, "1" for dimensionless */
    const char *description;
} dyn_var;

/* A named parameter: a double member of the model's parameter struct. */
typedef struct dyn_param {
    const char *name;
    const char *unit;
    const char *description;
    size_t offset;           /* offsetof(the struct, member) */
    double value;            /* default (the seed's value) */
} dyn_param;

/* Extra outputs at one sample: write n_outputs values into out; return 0 or non-zero. */
typedef int (*dyn_outputs_fn)(double t, const double *y, const void *par, double *out);
/* Prepare a parameter struct after parameters changed (derived values); 0 or non-zero
 * with a message in err. May be NULL. */
typedef int (*dyn_prepare_fn)(void *par, char *err, size_t errlen);
/* A warning about a state (e.g. near a singularity of the coordinates): a static message,
 * or NULL when all is well. May be NULL. */
typedef const char *(*dyn_warn_fn)(double t, const double *y, const void *par);

/* How a model reads a table of input samples between the sample times. */
typedef enum dyn_interp {
    DYN_INTERP_HOLD = 0,  /* zero-order hold at the nearest sample (the homework's rule) */
    DYN_INTERP_LINEAR = 1 /* linear interpolation between the neighbouring samples */
} dyn_interp;

/* Attach a time table of inputs to a prepared parameter struct: table is (rows x
 * (1 + n_inputs)) row-major, column 0 the time, strictly increasing, then the inputs in the
 * order of dyn_model.inputs. The table is borrowed: the caller keeps it alive while par is
 * used. Returns 0 or non-zero with a message in err. */
typedef int (*dyn_set_input_fn)(void *par, const double *table, long rows, dyn_interp interp,
                                char *err, size_t errlen);

/* A Poincaré map asked for by the model (XPPAUT's @ poimap, poivar, poipln, poisgn,
 * poistop): a run writes one row per crossing of the section instead of its samples. */
typedef enum dyn_poincare_kind {
    DYN_POINCARE_NONE = 0,
    DYN_POINCARE_SECTION = 1, /* var crosses plane (var "t": t = k * plane, a stroboscope) */
    DYN_POINCARE_EXTREMUM = 2, /* local maxima (sign 1), minima (-1) or both (0) of a state */
    DYN_POINCARE_PERIOD = 3   /* as SECTION, t replaced by the time since the last crossing */
} dyn_poincare_kind;
typedef struct dyn_poincare {
    int kind;          /* dyn_poincare_kind */
    const char *var;   /* a state, an output, or "t" */
    double plane;      /* the section's value (the period of a section in t) */
    int sign;          /* +1 rising, -1 falling, 0 both (extrema: maxima, minima, both) */
    int stop;          /* 1: the run stops at the first crossing */
} dyn_poincare;

typedef struct dyn_model {
    const char *name;          /* e.g. "pendulum" */
    const char *title;         /* one line */
    const char *description;   /* a paragraph: equations and conventions, plain text */
    int n_states;
    const dyn_var *states;     /* (n_states) */
    const double *y0;          /* (n_states) default initial state */
    int n_params;
    const dyn_param *params;   /* (n_params) */
    size_t par_size;           /* bytes of the parameter struct */
    int n_outputs;
    const dyn_var *outputs;    /* (n_outputs), may be NULL when n_outputs == 0 */
    dyn_rhs_fn rhs;
    dyn_outputs_fn compute_outputs;  /* NULL when n_outputs == 0 */
    dyn_prepare_fn prepare;    /* may be NULL */
    dyn_warn_fn warn;          /* may be NULL; checked at each output sample */
    double t0, t1, step;       /* default time span and step [s] */
    const char *method;        /* default method name (NULL: DYN_MODEL_METHOD) */
    /* Optional time-table input (e.g. applied forces), appended last so designated
     * initializers of models without inputs stay valid: n_inputs == 0 means none. */
    int n_inputs;
    const dyn_var *inputs;     /* (n_inputs) the input columns after t, names and units */
    dyn_set_input_fn set_input; /* NULL when n_inputs == 0 */
    /* Optional analytic Jacobian of rhs (NULL: finite differences where one is needed). */
    dyn_jac_fn jacobian;
    /* Named events of the model (e.g. the pendulum's "turn"), asked for with --event. */
    int n_events;
    const dyn_event *events;
    /* Samples of a default run with an adaptive method (no --step, no --times): the grid of
     * step, or every accepted step (DYN_SAMPLES_GRID = 0 when not set). `step` stays the
     * step of fixed-step methods. */
    dyn_sample_policy samples;
    /* Optional default initial state computed from the (prepared) parameters, for states
     * that depend on them (the plane hangs at l0 + m g/k below the ceiling); writes
     * n_states values. NULL: the fixed y0 above. */
    void (*initial_state)(const void *par, double *y0);
    /* Default tolerances of adaptive methods for this model (0: DYN_MODEL_RTOL and
     * DYN_MODEL_ATOL, the same for every kind of model): a model whose states are small
     * (chemical concentrations) carries the absolute tolerance it needs. --rtol/--atol
     * override. */
    double rtol, atol;
    /* The phase plane pictures show by default (XPPAUT's @ xp=, yp=): names of states or
     * outputs, or NULL. */
    const char *phase_x, *phase_y;
    /* Where the model was defined: a file path for models loaded from files, NULL for
     * built-in ones. */
    const char *source;
    /* Output and safety of a default run (XPPAUT's @ trans, nout, bound): samples before
     * t_trans are not written (0: from t0), every K-th sample is written (0 or 1: all),
     * and a run stops when a state's magnitude exceeds bound (0: no bound). */
    double t_trans;
    long every;
    double bound;
    /* Optional band of the Jacobian (jac_banded = 1): d f_i / d y_j = 0 unless
     * i - jac_lower <= j <= i + jac_upper; stiff methods then work with band matrices
     * (dyn_solve_opts.jac_banded). jacobian_band (may be NULL: banded differences) writes
     * the band in DYN_BAND_AT storage (ode.h). */
    int jac_banded;
    int jac_lower, jac_upper;
    dyn_jac_fn jacobian_band;
    /* The unit of the time t (NULL or "": s), e.g. "ms" for a neuron model (a model file's
     * `#: t [ms]`): the pages and plots label t with it. */
    const char *time_unit;
    /* The window of the phase plane, xlo, xhi, ylo, yhi (XPPAUT's @ xlo, xhi, ylo, yhi):
     * an axis whose lo < hi is drawn over it, else over the data (zeros). */
    double phase_window[4];
    /* Noise (a model file's wiener, normal(), ran(); dynkit/sde.h): n_noise slots, doubles
     * at byte noise_offset of the parameter struct that rhs reads and the solver writes
     * before each evaluation (0 outside a solve); noise_kinds[j] the dyn_noise_kind of slot
     * j, noise_class the dyn_noise_class of rhs (which methods can integrate it).
     * n_noise == 0: a deterministic model. */
    int n_noise;
    const int *noise_kinds;
    size_t noise_offset;
    int noise_class;
    /* A model whose prepare draws random numbers (a model file's table of ran() or
     * normal(), computed once: dyn_table_random): the byte offset of two doubles of the
     * parameter struct that hold the seed's low and high 32 bits, which the caller sets
     * before prepare (zero: seed 0); 0 for a model that draws nothing when prepared. */
    size_t seed_offset;
    /* Optional sparsity pattern of the Jacobian (jac_pattern.nnz > 0; CSC, dyn_sparse_pattern
     * in ode.h, every diagonal entry in it) and jacobian_sparse (may be NULL), which writes
     * its nnz values: a model file's exact Jacobian carries the pattern when it is sparse
     * (at least 32 states, at most a quarter of the entries), and jacobian_sparse too when
     * it is not banded. The tool's stiff runs then use a sparse LU (docs/stiff.md, "Sparse
     * Jacobians"). */
    dyn_sparse_pattern jac_pattern;
    dyn_jac_fn jacobian_sparse;
    /* Delay equations (XPPAUT's delay(x, tau)): NULL for a model without them. */
    const struct dyn_delay_model *delay;
    /* Volterra integrals (XPPAUT's int{...}, volt; dynkit/volterra.h): NULL for a model
     * without them. */
    const struct dyn_volterra_model *volterra;
    /* Jumps at the start of each step (a model file's Markov states; dynkit/sde.h,
     * dyn_jump_fn): read only by the methods for noise, so a model with jumps has noise
     * slots (n_noise > 0) for their random numbers. NULL: none. */
    dyn_jump_fn jump;
    /* Boundary conditions (a model file's bdry lines, XPPAUT's two-point boundary-value
     * problem on [t0, t1]): n_bdry residuals g(y(t0), y(t1), par) written by bdry, which
     * returns 0 or non-zero; bdry_text[k] the k-th condition as written, "LINE: text".
     * 0 and NULL: none. A run integrates the initial-value problem; `dynkit bvp` solves
     * them (dynkit/colloc.h). */
    int n_bdry;
    int (*bdry)(const double *yl, const double *yr, const void *par, double *g);
    const char *const *bdry_text;
    /* 1: the events are XPPAUT's globals (a model file's `global` lines), fired at XPPAUT's
     * instants (dyn_solve_opts.xppaut_globals, solve.h); 0: located to rounding. */
    int xppaut_globals;
    /* The Poincaré map of a default run (kind DYN_POINCARE_NONE: none). */
    dyn_poincare poincare;
    /* XPPAUT's hom_bcs(k) among the boundary conditions (projections onto an equilibrium's
     * eigen-subspaces for homoclinic and heteroclinic orbits; dynkit/colloc.h): NULL for a
     * model without them. */
    const struct dyn_hom_bcs *hom;
} dyn_model;

/* The projection conditions of a model file's bdry lines (XPPAUT's hom_bcs(k), its
 * (H)omoclinic dialog's settings read from the file): index[j] (n_bdry values) is k for the
 * condition hom_bcs(k), whose row of bdry writes 0 and the solver the projection, or -1 for
 * any other condition; the flow is the first dim states; the left end's equilibrium is held
 * in the states left .. left + dim - 1, the right end's in right .. right + dim - 1 (the
 * same for a homoclinic orbit); -1: not found in the file. */
typedef struct dyn_hom_bcs {
    const int *index;
    int dim, left, right;
} dyn_hom_bcs;

/* A model whose right-hand side reads its own past (dynkit/delay.h): its parameter struct
 * holds a pointer to the run's dyn_history, which the runner attaches before the solve and
 * feeds with the accepted steps. rhs, compute_outputs and the events read the past through
 * it; with none attached they return non-zero (DYN_DELAY_NO_HISTORY). */
#define DYN_DELAY_NO_HISTORY 77
struct dyn_history;
typedef struct dyn_delay_model {
    double max_delay;   /* the longest lag allowed (XPPAUT's @ delay=); 0: not given */
    /* store h (a struct dyn_history *, NULL detaches) in the parameter struct par */
    void (*attach)(void *par, struct dyn_history *h);
    /* state i before t0 (XPPAUT: x(0)= a formula of t; y0[i] for a state without one), or
     * NULL: the initial state y0 */
    double (*history)(int i, double t, const void *par, const double *y0);
    /* the lags that are constants (numbers and parameters): n_lags values into lags, for
     * the breaking points t0 + k tau where the steps land; lags that depend on the state or
     * t are not listed */
    int n_lags;
    void (*lags)(const void *par, double *lags);
} dyn_delay_model;

/* Version of the layout of dyn_model, dyn_var, dyn_param and dyn_event. A model compiled
 * into a shared object records the version it was built with (the symbol
 * dynkit_model_abi, added when dynkit compiles a model), and dynkit refuses a model built
 * for another version instead of misreading it. Raised whenever a layout changes. */
#define DYN_MODEL_ABI 11

/* The entry point of a model in a C file or a shared object: `dynkit run mymodel.c`
 * compiles the file and calls it. Define it in your file:
 *     const dyn_model *dynkit_model(void) { return &my_model; }   */
#define DYN_MODEL_ENTRY "dynkit_model"
typedef const struct dyn_model *(*dyn_model_entry_fn)(void);

/* Built-in models: count, by index (NULL out of range), by name (NULL if unknown). */
int dyn_model_count(void);
const dyn_model *dyn_model_at(int i);
const dyn_model *dyn_model_find(const char *name);
/* Comma-separated list of built-in model names into buf; returns buf. */
char *dyn_model_names(char *buf, size_t size);

/* Fill a parameter struct (par_size bytes, caller-owned, zeroed first) with the defaults,
 * then run prepare. Returns 0 or non-zero with a message in err. */
int dyn_model_default_params(const dyn_model *m, void *par, char *err, size_t errlen);
/* The default initial state for the parameters par (n_states values into y0): the model's
 * initial_state when it has one, else its fixed y0. */
void dyn_model_initial_state(const dyn_model *m, const void *par, double *y0);
/* Index of a state / parameter / output by name, or -1. */
int dyn_model_state_index(const dyn_model *m, const char *name);
int dyn_model_param_index(const dyn_model *m, const char *name);
int dyn_model_output_index(const dyn_model *m, const char *name);
/* Read / write parameter i of a parameter struct. */
double dyn_model_get_param(const dyn_model *m, const void *par, int i);
void dyn_model_set_param(const dyn_model *m, void *par, int i, double value);

/* For prepare functions: 0 if value is finite and > 0, else 1 with "NAME must be a finite
 * number > 0 (got V)" in err. */
int dyn_check_positive(const char *name, double value, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_MODEL_H */
