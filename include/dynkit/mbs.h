/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/mbs.h — mechanism files: bodies, joints by formulas, loads and constraints in;
 * the C text of a dyn_model out, its equations of motion derived by TMT (virtual power with
 * generalized coordinates). The syntax and the method are in docs/mechanisms.md.
 *
 * A mechanism becomes an ordinary dyn_model: the states are the coordinates and their
 * speeds, the outputs the constraints' multipliers (named after the constraints, with
 * units) and the energies. Part of the optional layer dynkit_lang; never prints or exits.
 */
#ifndef DYNKIT_MBS_H
#define DYNKIT_MBS_H

#include <stddef.h>

#include "dynkit/lang.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Translate the mechanism text (len bytes; path for messages) into C source, as
 * dyn_ode_to_c_tables does for an .ode file (tables: the files named for `table NAME FILE`
 * lines, may be NULL with n_tables 0): 0 and *c_source (malloc'd), or 2 (error in the
 * file, *diag filled with FILE:LINE:COL) or 1 (out of memory). */
int dyn_mech_to_c(const char *path, const char *text, size_t len,
                  const dyn_lang_table_file *tables, int n_tables, char **c_source,
                  dyn_lang_diag *diag, dyn_lang_note_fn note, void *note_ctx);

/* dyn_mech_to_c with flags: DYN_MECH_UNCHECKED_INIT leaves out the check that the
 * constraints hold at the file's initial state (the caller projects the state onto them
 * before a run; the checks of the mass matrix and the constraints' rows stay). */
#define DYN_MECH_UNCHECKED_INIT 1u
/* DYN_MECH_SCENE_INPUTS adds, after the model's outputs, one output per number the frames of
 * its scene are computed from (dyn_mech_scene_n_inputs, in their order, named scene:K; see
 * dyn_mech_scene_plan below): a program that runs the model's C can draw its scene without
 * reading the file (dynkit's live pages, docs/web.md). */
#define DYN_MECH_SCENE_INPUTS 2u
int dyn_mech_to_c_flags(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables, unsigned flags,
                        char **c_source, dyn_lang_diag *diag, dyn_lang_note_fn note,
                        void *note_ctx);

/* dyn_mech_to_c_flags with DYN_MECH_SCENE_INPUTS (and flags' DYN_MECH_UNCHECKED_INIT), then,
 * after the scene's inputs, one output per number of a frame of the XPPAUT animation
 * ani_text (ani_len bytes; ani_path names it in messages) read with the mechanism's names,
 * named ani:K, as dyn_ani_ode_to_c does for an .ode file (dynkit/ani.h): a program that runs
 * the model's C gets every frame of the animation with its sample (dynkit's live pages).
 * 0, or non-zero as dyn_mech_to_c with *diag (an error of either file). */
int dyn_mech_ani_to_c(const char *path, const char *text, size_t len,
                      const dyn_lang_table_file *tables, int n_tables, unsigned flags,
                      const char *ani_path, const char *ani_text, size_t ani_len,
                      char **c_source, dyn_lang_diag *diag);

/* What was derived, as readable formulas in the file's names (dynkit derive): the mass
 * matrix M (lower triangle), the forces F, and each constraint's row D and convective term
 * c, with M q'' = F + D' lambda and D q'' + c = 0; then the fixed quantities they use.
 * The constraints need not hold at the file's initial state (the formulas do not depend on
 * it); the mass matrix and the constraints' rows are checked there as dyn_mech_to_c does.
 * 0 and *out (malloc'd), or non-zero with *diag filled as dyn_mech_to_c. */
int dyn_mech_derive_text(const char *path, const char *text, size_t len, char **out,
                         dyn_lang_diag *diag);

/* The same mechanism as dyn_mech_to_c, but each constraint's output is its value on the
 * speeds, h = D(q, t) u + h_t(q, t) (for a holonomic constraint f(q, t) = 0, h = df/dt),
 * instead of its multiplier, with the unit "holonomic" or "speeds" saying which kind it
 * is; the other outputs, the states and the parameters (their struct) are those of
 * dyn_mech_to_c's model. After them, one output for each holonomic constraint: its value
 * f(q, t), named NAME:f, with the unit "position" ("prescribed" for a `prescribe`). The
 * constraints need not hold at the file's initial state. The admissible directions of the linearization come from it:
 * df/dq for the positions of holonomic ones, (dh/dq, dh/du) for all (docs/analysis.md). */
int dyn_mech_constraints_to_c(const char *path, const char *text, size_t len,
                              const dyn_lang_table_file *tables, int n_tables, char **c_source,
                              dyn_lang_diag *diag);

/* ---- the picture of a mechanism (docs/mechanisms.md, "Geometry to draw") ----
 * The geometry statements of the file (box, cylinder, disk, sphere, rod, frame, ground,
 * trace, arrow), or a default drawing when it has none (a sphere per point mass, the axes
 * and a sphere per rigid body), and the springs, and the wheels (a disk, and the forces of
 * their rolling constraints at the contact point), evaluated for the frames of a recorded run:
 * the bodies' poses and every shape's numbers in N. */

typedef enum dyn_mech_shape_kind {
    DYN_MECH_BOX,      /* centre (3), half sizes along the body's axes (3) */
    DYN_MECH_CYLINDER, /* centre (3), radius, half length (0: a disk), unit axis in N (3) */
    DYN_MECH_SPHERE,   /* centre (3), radius (NaN: the page's size) */
    DYN_MECH_ROD,      /* end a (3), end b (3) */
    DYN_MECH_SPRING,   /* end a (3), end b (3) */
    DYN_MECH_FRAME,    /* origin (3), length of the axes (NaN: the page's size) */
    DYN_MECH_GROUND,   /* a point (3), the normal (3), half size (NaN: the page's size) */
    DYN_MECH_TRACE,    /* the point (3) whose path is drawn */
    DYN_MECH_ARROW,    /* the point (3), the unit direction (3) of a constraint's force */
    DYN_MECH_SHAPE_COUNT
} dyn_mech_shape_kind;

typedef struct dyn_mech_shape {
    dyn_mech_shape_kind kind;
    const char *name;  /* the statement's name, or the body's or spring's */
    int line, col;     /* where it is written (0: a default shape) */
    int body;          /* its body (the pose's orientation), -1: the ground */
    int axis;          /* a cylinder's axis in the body frame: 0 x, 1 y, 2 z (-1: a wheel's) */
    const char *color; /* "#rrggbb", or NULL: the run's colour */
    int constraint;    /* an arrow's constraint (index of dyn_mech_scene_constraint) */
    int offset;        /* its numbers in a frame: values[offset .. offset + n_values) */
    int n_values;
} dyn_mech_shape;

typedef struct dyn_mech_scene dyn_mech_scene;

/* Read the mechanism text as dyn_mech_to_c does (the same errors at FILE:LINE:COL), without
 * deriving its equations: 0 and *scene (release with dyn_mech_scene_free), or 2 (error in
 * the file, *diag filled) or 1 (out of memory). */
int dyn_mech_scene_read(const char *path, const char *text, size_t len,
                        const dyn_lang_table_file *tables, int n_tables,
                        dyn_mech_scene **scene, dyn_lang_diag *diag);
void dyn_mech_scene_free(dyn_mech_scene *scene);

int dyn_mech_scene_n_bodies(const dyn_mech_scene *s);
const char *dyn_mech_scene_body_name(const dyn_mech_scene *s, int body);
/* 1 for a point mass without a frame of its own (its offsets are in N) */
int dyn_mech_scene_body_is_point(const dyn_mech_scene *s, int body);
int dyn_mech_scene_n_shapes(const dyn_mech_scene *s);
const dyn_mech_shape *dyn_mech_scene_shape(const dyn_mech_scene *s, int i);
int dyn_mech_scene_n_values(const dyn_mech_scene *s); /* shapes' numbers of one frame */
int dyn_mech_scene_n_constraints(const dyn_mech_scene *s);
/* a constraint's name (its multiplier's output) */
const char *dyn_mech_scene_constraint(const dyn_mech_scene *s, int k);
/* the parameters the frames take: the model's, in its order (then derived ones follow) */
int dyn_mech_scene_n_params(const dyn_mech_scene *s);
/* gravity at the default parameters, (0, 0, 0) when none */
void dyn_mech_scene_gravity(const dyn_mech_scene *s, double g[3]);
/* the mass of all bodies and point masses at the default parameters and initial state (kg;
 * the scale m |g| below which the page draws no constraint force) */
double dyn_mech_scene_mass(const dyn_mech_scene *s);

/* One frame: t, the states y (the model's: coordinates, then speeds) and the parameters
 * (dyn_mech_scene_n_params values, the model's order). Into pose (12 per body: the mass
 * centre in N, then R row-major, R mapping N-coordinates to B-coordinates; the identity for
 * a point mass without a frame) and values (dyn_mech_scene_n_values). Returns 0, or 1 when out of memory.
 * Re-entrant. */
int dyn_mech_scene_eval(const dyn_mech_scene *s, double t, const double *y,
                        const double *params, double *pose, double *values);

/* ---- the plan of a frame, for a program that evaluates frames itself ----
 * A frame is computed from the scene's inputs (the numbers of the file's formulas at t, the
 * states and the parameters: the outputs scene:K of DYN_MECH_SCENE_INPUTS) by the steps of
 * dyn_mech_scene_eval. Every field below that names an input is its index K, or -1 when
 * the file gives none (its default then: 0, or NaN for a size the page chooses). */
#define DYN_MECH_MAX_ROT 12

typedef struct dyn_mech_body_plan {
    int frame;                    /* 1: R from the rotations or quat; 0: the identity */
    int quat[4];                  /* Euler parameters (w, x, y, z), or quat[0] = -1 */
    int nrot;                     /* elementary rotations R = E_nrot ... E_1 */
    int axis[DYN_MECH_MAX_ROT];   /* 0 x, 1 y, 2 z, 3 the joint's axis axisv */
    int angle[DYN_MECH_MAX_ROT];  /* inputs */
    int joint;                    /* 0: placed at `at`; else x = x_P + R_P'(jp + shift +
                                     n slide) - R'(pivot) (R' pivot: pivot when no frame) */
    int parent;                   /* -1: the ground */
    int at[3], jp[3], shift[3], pivot[3], axisv[3]; /* inputs */
    int slide, slide_axis;        /* a prismatic joint's input and axis (0-2, 3: axisv) */
    int mass;                     /* input */
} dyn_mech_body_plan;

typedef struct dyn_mech_shape_plan {
    int body, p[3];       /* point a: its body (-1: the ground) and offset (inputs) */
    int body_b, p_b[3];   /* a rod's or spring's end b */
    int v[3];             /* inputs: sizes, an arrow's direction, the ground's normal */
    int size;             /* input: a frame's or the ground's size */
    int axis;             /* a cylinder's axis 0..2 in its body (-1: avec) */
    int avec[3];          /* inputs: a cylinder's axis as a vector of its body */
    int in_body;          /* an arrow's direction is in its body's frame */
    int wheel;            /* a wheel's disk or contact arrow (index of the wheels), or -1 */
} dyn_mech_shape_plan;

typedef struct dyn_mech_wheel_plan {
    int body, radius, axis[3], at[3]; /* inputs; axis and centre in the body's frame */
} dyn_mech_wheel_plan;

int dyn_mech_scene_n_inputs(const dyn_mech_scene *s);
int dyn_mech_scene_n_wheels(const dyn_mech_scene *s);
/* 0, or -1 for an index out of range */
int dyn_mech_scene_body_plan(const dyn_mech_scene *s, int body, dyn_mech_body_plan *out);
int dyn_mech_scene_shape_plan(const dyn_mech_scene *s, int i, dyn_mech_shape_plan *out);
int dyn_mech_scene_wheel_plan(const dyn_mech_scene *s, int w, dyn_mech_wheel_plan *out);
void dyn_mech_scene_gravity_inputs(const dyn_mech_scene *s, int g[3]);

#ifdef __cplusplus
}
#endif
#endif /* DYNKIT_MBS_H */
