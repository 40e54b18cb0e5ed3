/* SPDX-License-Identifier: BSD-3-Clause */
/* Butcher tables of the explicit Runge–Kutta methods, as data in one place.
 *
 * Coefficients: Hairer, Nørsett & Wanner, "Solving Ordinary Differential Equations I",
 * 2nd ed., sec. II.1 (Euler, Heun, midpoint, Runge's RK4, Kutta's 3/8 rule) and
 * A. Ralston, "Runge-Kutta methods with minimum error bounds", Math. Comp. 16 (1962).
 * Heun's method is the homework's "modified Euler" (Greenwood, "Advanced Dynamics", p. 341):
 * predictor y~ = y + h f(t, y), corrector y + h/2 (f(t, y) + f(t + h, y~)).
 *
 * Embedded pairs (adaptive, run by dyn_solve):
 * - bs23: P. Bogacki & L. F. Shampine, "A 3(2) pair of Runge-Kutta formulas", Appl. Math.
 *   Lett. 2 (1989) 321-325 (MATLAB's ode23); FSAL; dense output the cubic Hermite
 *   interpolant of the step written in the stages (as in SciPy's RK23).
 * - dp45: J. R. Dormand & P. J. Prince, "A family of embedded Runge-Kutta formulae",
 *   J. Comput. Appl. Math. 6 (1980) 19-26 (MATLAB's ode45, Hairer's DOPRI5); FSAL; dense
 *   output of order 4 of Hairer's DOPRI5 (HNW I sec. II.6, after Shampine, Math. Comp. 46
 *   (1986); the same polynomial as SciPy's RK45.P, checked in exact rational arithmetic).
 * - dop853: E. Hairer & G. Wanner's DOP853 (dop853.f, 1993; HNW I sec. II.10): order 8,
 *   error estimators of orders 5 and 3, dense output of order 7 with three extra stages.
 *   Digits as in dop853.f and SciPy's scipy/integrate/_ivp/dop853_coefficients.py; the
 *   arrays are printed by tools/dop853_tables.py. Checked by the order conditions of all
 *   200 rooted trees up to order 8 (tests/test_adaptive.c).
 * Dense output is stored in Hairer's nested form (dyn_dense in solve.h): every explicit
 * method shares the cubic Hermite part; `dense` holds the rows of the higher corrections.
 * Every table is driven by the one stage loop in rk_stages.h.
 */
#include <stdio.h>
#include <string.h>

#include "dynkit/ode.h"
#include "ode/rosenbrock.h"

static const double euler_a[] = {0.0};
static const double euler_b[] = {1.0};
static const double euler_c[] = {0.0};

static const double heun_a[] = {0.0, 0.0,
                                1.0, 0.0};
static const double heun_b[] = {0.5, 0.5};
static const double heun_c[] = {0.0, 1.0};

static const double midpoint_a[] = {0.0, 0.0,
                                    0.5, 0.0};
static const double midpoint_b[] = {0.0, 1.0};
static const double midpoint_c[] = {0.0, 0.5};

static const double ralston_a[] = {0.0, 0.0,
                                   2.0 / 3.0, 0.0};
static const double ralston_b[] = {0.25, 0.75};
static const double ralston_c[] = {0.0, 2.0 / 3.0};

static const double rk4_a[] = {0.0, 0.0, 0.0, 0.0,
                               0.5, 0.0, 0.0, 0.0,
                               0.0, 0.5, 0.0, 0.0,
                               0.0, 0.0, 1.0, 0.0};
static const double rk4_b[] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
static const double rk4_c[] = {0.0, 0.5, 0.5, 1.0};

static const double rk38_a[] = {0.0, 0.0, 0.0, 0.0,
                                1.0 / 3.0, 0.0, 0.0, 0.0,
                                -1.0 / 3.0, 1.0, 0.0, 0.0,
                                1.0, -1.0, 1.0, 0.0};
static const double rk38_b[] = {1.0 / 8.0, 3.0 / 8.0, 3.0 / 8.0, 1.0 / 8.0};
static const double rk38_c[] = {0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0};

/* ---- Bogacki–Shampine 3(2), FSAL ---- */
static const double bs23_a[] = {0.0, 0.0, 0.0, 0.0,
                                0.5, 0.0, 0.0, 0.0,
                                0.0, 0.75, 0.0, 0.0,
                                2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0, 0.0};
static const double bs23_b[] = {2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0, 0.0};
static const double bs23_c[] = {0.0, 0.5, 0.75, 1.0};
/* b - bhat, bhat = (7/24, 1/4, 1/3, 1/8) of order 2 */
static const double bs23_e[] = {5.0 / 72.0, -1.0 / 12.0, -1.0 / 9.0, 1.0 / 8.0};

/* ---- Dormand–Prince 5(4), FSAL ---- */
static const double dp45_a[] = {
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0, 0.0,
    19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0, 0.0,
    9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0, 0.0,
    35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0, 0.0};
static const double dp45_b[] = {35.0 / 384.0,     0.0,         500.0 / 1113.0, 125.0 / 192.0,
                                -2187.0 / 6784.0, 11.0 / 84.0, 0.0};
static const double dp45_c[] = {0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0};
/* b - bhat, bhat = (5179/57600, 0, 7571/16695, 393/640, -92097/339200, 187/2100, 1/40) */
static const double dp45_e[] = {71.0 / 57600.0,      0.0,          -71.0 / 16695.0, 71.0 / 1920.0,
                                -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0};
/* the correction of DOPRI5's dense output to the cubic Hermite interpolant: c4 = h sum d_i
 * k_i, times theta^2 (1-theta)^2 (Hairer's D1..D7, Shampine 1986) */
static const double dp45_dense[] = {-12715105075.0 / 11282082432.0, 0.0,
                                    87487479700.0 / 32700410799.0,  -10690763975.0 / 1880347072.0,
                                    701980252875.0 / 199316789632.0, -1453857185.0 / 822651844.0,
                                    69997945.0 / 29380423.0};

/* ---- DOP853: 12 stages; stage 12 of the dense output is f(t + h, y_{n+1}) ---- */
static const double dop853_a[] = {
    /* stage 0 */
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    /* stage 1 */
    5.26001519587677318785587544488e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    /* stage 2 */
    1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0,
    /* stage 3 */
    2.95875854768068491816892993775e-2, 0.0, 8.87627564304205475450678981324e-2, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0,
    /* stage 4 */
    2.41365134159266685502369798665e-1, 0.0, -8.84549479328286085344864962717e-1,
    9.24834003261792003115737966543e-1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    /* stage 5 */
    3.7037037037037037037037037037e-2, 0.0, 0.0, 1.70828608729473871279604482173e-1,
    1.25467687566822425016691814123e-1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    /* stage 6 */
    3.7109375e-2, 0.0, 0.0, 1.70252211019544039314978060272e-1, 6.02165389804559606850219397283e-2,
    -1.7578125e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    /* stage 7 */
    3.70920001185047927108779319836e-2, 0.0, 0.0, 1.70383925712239993810214054705e-1,
    1.07262030446373284651809199168e-1, -1.53194377486244017527936158236e-2,
    8.27378916381402288758473766002e-3, 0.0, 0.0, 0.0, 0.0, 0.0,
    /* stage 8 */
    6.24110958716075717114429577812e-1, 0.0, 0.0, -3.36089262944694129406857109825,
    -8.68219346841726006818189891453e-1, 2.75920996994467083049415600797e1,
    2.01540675504778934086186788979e1, -4.34898841810699588477366255144e1, 0.0, 0.0, 0.0, 0.0,
    /* stage 9 */
    4.77662536438264365890433908527e-1, 0.0, 0.0, -2.48811461997166764192642586468,
    -5.90290826836842996371446475743e-1, 2.12300514481811942347288949897e1,
    1.52792336328824235832596922938e1, -3.32882109689848629194453265587e1,
    -2.03312017085086261358222928593e-2, 0.0, 0.0, 0.0,
    /* stage 10 */
    -9.3714243008598732571704021658e-1, 0.0, 0.0, 5.18637242884406370830023853209,
    1.09143734899672957818500254654, -8.14978701074692612513997267357,
    -1.85200656599969598641566180701e1, 2.27394870993505042818970056734e1,
    2.49360555267965238987089396762, -3.0467644718982195003823669022, 0.0, 0.0,
    /* stage 11 */
    2.27331014751653820792359768449, 0.0, 0.0, -1.05344954667372501984066689879e1,
    -2.00087205822486249909675718444, -1.79589318631187989172765950534e1,
    2.79488845294199600508499808837e1, -2.85899827713502369474065508674,
    -8.87285693353062954433549289258, 1.23605671757943030647266201528e1,
    6.43392746015763530355970484046e-1, 0.0,
};
static const double dop853_b[] = {
    5.42937341165687622380535766363e-2, 0.0, 0.0, 0.0, 0.0, 4.45031289275240888144113950566,
    1.89151789931450038304281599044, -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1, -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1, 4.47106157277725905176885569043e-2,
};
static const double dop853_c[] = {
    0.0, 0.526001519587677318785587544488e-01, 0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510, 0.281649658092772603273242802490,
    0.333333333333333333333333333333, 0.25, 0.307692307692307692307692307692,
    0.651282051282051282051282051282, 0.6, 0.857142857142857142857142857142, 1.0,
};
static const double dop853_e[] = {
    0.1312004499419488073250102996e-1, 0.0, 0.0, 0.0, 0.0, -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952, 0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290, 0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1, -0.2235530786388629525884427845e-1,
};
static const double dop853_e3[] = {
    5.42937341165687622380535766363e-2 - 0.244094488188976377952755905512, 0.0, 0.0, 0.0, 0.0,
    4.45031289275240888144113950566, 1.89151789931450038304281599044,
    -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1 - 0.733846688281611857341361741547,
    -1.52160949662516078556178806805e-1, 2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2 - 0.220588235294117647058823529412e-1,
};
static const double dop853_dense_c[] = {
    0.1, 0.2, 0.777777777777777777777777777778,
};
static const double dop853_dense_a[] = {
    /* stage 13 */
    5.61675022830479523392909219681e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 2.53500210216624811088794765333e-1,
    -2.46239037470802489917441475441e-1, -1.24191423263816360469010140626e-1,
    1.5329179827876569731206322685e-1, 8.20105229563468988491666602057e-3,
    7.56789766054569976138603589584e-3, -8.298e-3, 0.0, 0.0, 0.0,
    /* stage 14 */
    3.18346481635021405060768473261e-2, 0.0, 0.0, 0.0, 0.0, 2.83009096723667755288322961402e-2,
    5.35419883074385676223797384372e-2, -5.49237485713909884646569340306e-2, 0.0, 0.0,
    -1.08347328697249322858509316994e-4, 3.82571090835658412954920192323e-4,
    -3.40465008687404560802977114492e-4, 1.41312443674632500278074618366e-1, 0.0, 0.0,
    /* stage 15 */
    -4.28896301583791923408573538692e-1, 0.0, 0.0, 0.0, 0.0, -4.69762141536116384314449447206,
    7.68342119606259904184240953878, 4.06898981839711007970213554331,
    3.56727187455281109270669543021e-1, 0.0, 0.0, 0.0, -1.39902416515901462129418009734e-3,
    2.9475147891527723389556272149, -9.15095847217987001081870187138, 0.0,
};
static const double dop853_dense[] = {
    /* c4 = h sum_i D[0][i] k_i */
    -0.84289382761090128651353491142e1, 0.0, 0.0, 0.0, 0.0, 0.56671495351937776962531783590,
    -0.30689499459498916912797304727e1, 0.23846676565120698287728149680e1,
    0.21170345824450282767155149946e1, -0.87139158377797299206789907490,
    0.22404374302607882758541771650e1, 0.63157877876946881815570249290,
    -0.88990336451333310820698117400e-1, 0.18148505520854727256656404962e2,
    -0.91946323924783554000451984436e1, -0.44360363875948939664310572000e1,
    /* c5 = h sum_i D[1][i] k_i */
    0.10427508642579134603413151009e2, 0.0, 0.0, 0.0, 0.0, 0.24228349177525818288430175319e3,
    0.16520045171727028198505394887e3, -0.37454675472269020279518312152e3,
    -0.22113666853125306036270938578e2, 0.77334326684722638389603898808e1,
    -0.30674084731089398182061213626e2, -0.93321305264302278729567221706e1,
    0.15697238121770843886131091075e2, -0.31139403219565177677282850411e2,
    -0.93529243588444783865713862664e1, 0.35816841486394083752465898540e2,
    /* c6 = h sum_i D[2][i] k_i */
    0.19985053242002433820987653617e2, 0.0, 0.0, 0.0, 0.0, -0.38703730874935176555105901742e3,
    -0.18917813819516756882830838328e3, 0.52780815920542364900561016686e3,
    -0.11573902539959630126141871134e2, 0.68812326946963000169666922661e1,
    -0.10006050966910838403183860980e1, 0.77771377980534432092869265740,
    -0.27782057523535084065932004339e1, -0.60196695231264120758267380846e2,
    0.84320405506677161018159903784e2, 0.11992291136182789328035130030e2,
    /* c7 = h sum_i D[3][i] k_i */
    -0.25693933462703749003312586129e2, 0.0, 0.0, 0.0, 0.0, -0.15418974869023643374053993627e3,
    -0.23152937917604549567536039109e3, 0.35763911791061412378285349910e3,
    0.93405324183624310003907691704e2, -0.37458323136451633156875139351e2,
    0.10409964950896230045147246184e3, 0.29840293426660503123344363579e2,
    -0.43533456590011143754432175058e2, 0.96324553959188282948394950600e2,
    -0.39177261675615439165231486172e2, -0.14972683625798562581422125276e3,
};

#define TABLE(nm, al, ti, ref, s, p, pre)                                                    \
    {.name = nm, .alias = al, .title = ti, .reference = ref, .kind = DYN_KIND_EXPLICIT_RK,     \
     .stages = s, .order = p, .a = pre##_a, .b = pre##_b, .c = pre##_c}

static const double rodas4_stage_times[] = {0.0, 0.386, 0.21, 0.63, 1.0, 1.0};

static const dyn_tableau methods[] = {
    TABLE("euler", NULL, "explicit Euler, y + h f(t, y)", "Euler 1768; HNW I sec. II.1", 1, 1,
          euler),
    TABLE("heun", "modified-euler", "Heun / modified Euler: Euler predictor, trapezoidal corrector",
          "Greenwood, Advanced Dynamics, p. 341; HNW I sec. II.1", 2, 2, heun),
    TABLE("midpoint", "rk2", "explicit midpoint rule (RK2)", "Runge 1895; HNW I sec. II.1", 2, 2,
          midpoint),
    TABLE("ralston", NULL, "Ralston's 2nd-order method (minimum error bound)",
          "Ralston, Math. Comp. 16 (1962)", 2, 2, ralston),
    TABLE("rk4", NULL, "classical 4th-order Runge-Kutta", "Kutta 1901; HNW I table 1.2", 4, 4, rk4),
    TABLE("rk38", NULL, "Kutta's 3/8 rule, 4th order", "Kutta 1901; HNW I table 1.2", 4, 4, rk38),
    {.name = "bs23",
     .alias = "ode23",
     .title = "Bogacki-Shampine 3(2) pair, FSAL, cubic Hermite dense output (MATLAB's ode23)",
     .reference = "Bogacki & Shampine, Appl. Math. Lett. 2 (1989) 321-325",
     .kind = DYN_KIND_EMBEDDED_RK,
     .stages = 4,
     .order = 3,
     .a = bs23_a,
     .b = bs23_b,
     .c = bs23_c,
     .e = bs23_e,
     .embedded_order = 2,
     .error_order = 2,
     .fsal = 1,
     .dense_degree = 3,
     /* MATLAB's ode23 (Shampine & Reichelt 1997): with SciPy's 0.9 the pair rejects more
      * steps and needs 6% more calls at equal error at errors above 1e-6, as many below
      * (30 problems: docs/solvers.md, "Each pair's controller") */
     .safety = 0.8},
    {.name = "dp45",
     .alias = "ode45",
     .title = "Dormand-Prince 5(4) pair, FSAL, 4th-order dense output (MATLAB's ode45, DOPRI5)",
     .reference = "Dormand & Prince, J. Comput. Appl. Math. 6 (1980) 19-26; HNW I sec. II.5-6",
     .kind = DYN_KIND_EMBEDDED_RK,
     .stages = 7,
     .order = 5,
     .a = dp45_a,
     .b = dp45_b,
     .c = dp45_c,
     .e = dp45_e,
     .embedded_order = 4,
     .error_order = 4,
     .fsal = 1,
     .dense_degree = 4,
     .dense_stages = 7,
     .dense = dp45_dense,
     .stiff_stage = 5,
     .stiff_bound = 3.25,
     /* MATLAB's ode45 (Shampine & Reichelt 1997) and HNW I sec. II.4's usual 0.8: with
      * dopri5.f's 0.9 the pair needs 6% more calls at equal error over 30 problems, 14% more
      * at errors above 1e-6 (docs/solvers.md, "Each pair's controller") */
     .safety = 0.8},
    {.name = "dop853",
     .alias = NULL,
     .title = "Hairer-Wanner DOP853: order 8, error estimators 5 and 3, 7th-order dense output",
     .reference = "Hairer, Norsett & Wanner I sec. II.10; dop853.f (Hairer & Wanner 1993)",
     .kind = DYN_KIND_EMBEDDED_RK,
     .stages = 12,
     .order = 8,
     .a = dop853_a,
     .b = dop853_b,
     .c = dop853_c,
     .e = dop853_e,
     .e3 = dop853_e3,
     .embedded_order = 5,
     .error_order = 7,
     .fsal = 0,
     .dense_degree = 7,
     .dense_stages = 16,
     .dense = dop853_dense,
     .dense_a = dop853_dense_a,
     .dense_c = dop853_dense_c,
     .stiff_stage = 11,
     .stiff_bound = 6.1,
     /* between HNW I sec. II.4's usual 0.8 and 0.9: with dop853.f's 0.9 the pair rejects
      * more steps and needs 3% more calls at equal error over 30 problems, 5% more at errors
      * below 1e-6 (docs/solvers.md, "Each pair's controller") */
     .safety = 0.85},
    /* stiff: Rosenbrock methods, coefficients in src/ode/rosenbrock_tables.c */
    {.name = "rodas4",
     .alias = "rodas",
     .title = "Hairer-Wanner RODAS 4(3): Rosenbrock, L-stable, stiffly accurate, for stiff "
              "problems",
     .reference = "Hairer & Wanner II sec. IV.7; rodas.f (ROCOE, METH = 1)",
     .kind = DYN_KIND_ROSENBROCK,
     .stages = 6,
     .order = 4,
     .c = rodas4_stage_times,
     .embedded_order = 3,
     .error_order = 3,
     .dense_degree = 3,
     .impl = &dyn_ros_rodas4},
    /* not an integrator: f is the map itself (one evaluation per step, no coefficients
     * used; Euler's single-stage table keeps every reader of a, b, c safe) */
    {.name = "discrete",
     .alias = "map",
     .title = "discrete map: y_{k+1} = f(t_k, y_k), t_{k+1} = t_k + h (XPPAUT's meth=discrete)",
     .reference = "XPPAUT's difference equations (x(t+1)=, meth=discrete)",
     .kind = DYN_KIND_MAP,
     .stages = 1,
     .order = 0,
     .a = euler_a,
     .b = euler_b,
     .c = euler_c},
};

int dyn_method_count(void) { return (int)(sizeof methods / sizeof methods[0]); }

const dyn_tableau *dyn_method_at(int i)
{
    return (i >= 0 && i < dyn_method_count()) ? &methods[i] : NULL;
}

const dyn_tableau *dyn_method_find(const char *name)
{
    if (!name)
        return NULL;
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = &methods[i];
        if (strcmp(m->name, name) == 0 || (m->alias && strcmp(m->alias, name) == 0))
            return m;
    }
    return NULL;
}

int dyn_method_is_adaptive(const dyn_tableau *m)
{
    return m && m->kind != DYN_KIND_EXPLICIT_RK && m->kind != DYN_KIND_MAP;
}

int dyn_method_is_stiff(const dyn_tableau *m)
{
    return m && dyn_method_is_adaptive(m) && m->kind != DYN_KIND_EMBEDDED_RK;
}

int dyn_method_is_map(const dyn_tableau *m) { return m && m->kind == DYN_KIND_MAP; }

/* Calls of f in a Rosenbrock step from a new point: f(t, y) (the stages with alpha_i = 0
 * and no a_ij reuse it), one per other stage, and one for df/dt (step_rosenbrock.c). */
static int ros_calls_per_step(const dyn_ros_method *rm)
{
    int calls = 2;
    for (int i = 0; i < rm->stages; i++) {
        int own = rm->alpha[i] != 0.0;
        for (int j = 0; j < i; j++)
            own |= rm->a[(size_t)i * (size_t)rm->stages + (size_t)j] != 0.0;
        calls += own;
    }
    return calls;
}

int dyn_method_calls_per_step(const dyn_tableau *m)
{
    if (!m)
        return 0;
    if (m->kind == DYN_KIND_ROSENBROCK && m->impl)
        return ros_calls_per_step((const dyn_ros_method *)m->impl);
    return m->stages - (m->fsal ? 1 : 0);
}

int dyn_method_jac_per_step(const dyn_tableau *m)
{
    return dyn_method_is_stiff(m) ? 1 : 0;
}

char *dyn_method_names(char *buf, size_t size)
{
    size_t used = 0;
    if (size == 0)
        return buf;
    buf[0] = '\0';
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = &methods[i];
        int w = snprintf(buf + used, size - used, "%s%s%s%s%s", i ? ", " : "", m->name,
                         m->alias ? " (" : "", m->alias ? m->alias : "", m->alias ? ")" : "");
        if (w < 0 || (size_t)w >= size - used)
            break;
        used += (size_t)w;
    }
    return buf;
}
