/* ark1.c: ARKODE on first-order systems (ark1.h): ERKStep, ARKStep IMEX
 * with a banded Newton solve, MRIStep with an inner ARKStep ERK.
 *
 * The implicit part of IMEX is solved by ARKODE's modified Newton
 * iteration with a banded direct linear solver (SUNDIALS band matrix and
 * solver, in libsundials_arkode of Debian's 6.4.1) and the Jacobian by
 * banded difference quotients (2 band + 1 evaluations of fi, counted in
 * the evaluations).  The ERK tables with c_s = 1 that are not FSAL are
 * padded against the issue-311 trap (arkode.c) for ERKStep and for the
 * inner explicit method of MRIStep.  ARKStep's IMEX pairs (ARK324L2SA,
 * ARK436L2SA, ARK548L2SA) are used as ARKStep defines them
 * (tests/test_film_imex.c: IMEX at tight tolerance agrees with the ERK
 * reference on the film). */
#include "integrators/ark1.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <arkode/arkode_mristep.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include "integrators/arkode.h"
#include "integrators/stop.h"

struct bf_ark1 {
    bf_ark1_opts o;
    size_t n;
    bf_rhs_fn fe, fi;
    void *ctx;
    SUNContext sunctx;
    void *mem;   /* ERKStep, ARKStep or MRIStep */
    void *inner; /* MRI: the inner ARKStep */
    MRIStepInnerStepper stepper;
    N_Vector y;
    SUNMatrix A;
    SUNLinearSolver LS;
    int order, padded;
    double h_next;
    bf_counters base; /* counted before a checkpoint was loaded */
    int failed; /* a right-hand side asked to stop */
    int stopped; /* the run's stop flag ended the call (stop.h) */
    long steps_set; /* ARKODE's limit of internal steps per call now */
    char msg[512];
    /* kinks (ERK, bf_ark1_set_kinks): g, its size, and the states at the start (prev) and end (cur) of the last step */
    bf_root1_fn g;
    int ng;
    double tprev, tcur;
    double *yprev, *ycur;
    unsigned long long restarts;
};

/* A call that lasts (a million internal steps of a tiny max_step) ends at
 * the next evaluation after the run's stop flag is set. */
static int stop_now(bf_ark1 *a)
{
    if (!bf_stop_requested())
        return 0;
    a->stopped = 1;
    return 1;
}

static int rhs_e(realtype t, N_Vector y, N_Vector yd, void *ud)
{
    bf_ark1 *a = ud;
    if (stop_now(a))
        return -1;
    int r = a->fe(a->ctx, t, N_VGetArrayPointer(y), N_VGetArrayPointer(yd));
    if (r < 0)
        a->failed = 1;
    return r;
}

static int rhs_i(realtype t, N_Vector y, N_Vector yd, void *ud)
{
    bf_ark1 *a = ud;
    if (stop_now(a))
        return -1;
    int r = a->fi(a->ctx, t, N_VGetArrayPointer(y), N_VGetArrayPointer(yd));
    if (r < 0)
        a->failed = 1;
    return r;
}

static void errh(int code, const char *module, const char *function,
                 char *msg, void *ud)
{
    (void)module;
    bf_ark1 *a = ud;
    if (code < 0)
        snprintf(a->msg, sizeof a->msg, "%s: %s", function, msg);
}

static const char *flag_name(const bf_ark1 *a, int flag)
{
    return a->o.kind == BF_ARK1_ERK    ? ERKStepGetReturnFlagName(flag)
           : a->o.kind == BF_ARK1_IMEX ? ARKStepGetReturnFlagName(flag)
                                       : MRIStepGetReturnFlagName(flag);
}

static bf_status check(bf_ark1 *a, int flag, const char *what, bf_err *err)
{
    if (flag >= 0)
        return BF_OK;
    return bf_fail(err, BF_EINTERNAL, "ARKODE %s failed (%s)%s%s", what,
                   flag_name(a, flag), a->msg[0] ? ": " : "", a->msg);
}

void bf_ark1_free(bf_ark1 *a)
{
    if (!a)
        return;
    if (a->o.kind == BF_ARK1_ERK && a->mem)
        ERKStepFree(&a->mem);
    if (a->o.kind == BF_ARK1_IMEX && a->mem)
        ARKStepFree(&a->mem);
    if (a->o.kind == BF_ARK1_MRI) {
        if (a->mem)
            MRIStepFree(&a->mem);
        if (a->stepper)
            MRIStepInnerStepper_Free(&a->stepper);
        if (a->inner)
            ARKStepFree(&a->inner);
    }
    if (a->LS)
        SUNLinSolFree(a->LS);
    if (a->A)
        SUNMatDestroy(a->A);
    if (a->y)
        N_VDestroy(a->y);
    if (a->sunctx)
        SUNContext_Free(&a->sunctx);
    free(a->yprev);
    free(a->ycur);
    free(a);
}

/* The explicit table (padded when it needs it). */
static ARKodeButcherTable erk_table(bf_ark1 *a, bf_err *err)
{
    ARKodeButcherTable B =
        bf_arkode_erk_table(a->o.table, a->o.work_around_311, &a->padded);
    if (!B)
        bf_fail(err, BF_EINTERNAL, "cannot load the ARKODE table %d",
                a->o.table);
    else if (!B->d) {
        bf_fail(err, BF_EINPUT, "%s has no embedded method, so it cannot "
                "adapt its step", bf_arkode_table_name(a->o.table));
        ARKodeButcherTable_Free(B);
        B = NULL;
    }
    return B;
}

static bf_status create_erk(bf_ark1 *a, bf_err *err)
{
    ARKodeButcherTable B = erk_table(a, err);
    if (!B)
        return err->status;
    a->order = B->q;
    a->mem = ERKStepCreate(rhs_e, 0.0, a->y, a->sunctx);
    int flag = a->mem ? 0 : -1;
    if (flag >= 0)
        flag = ERKStepSetErrHandlerFn(a->mem, errh, a);
    if (flag >= 0)
        flag = ERKStepSetUserData(a->mem, a);
    if (flag >= 0)
        flag = ERKStepSetTable(a->mem, B);
    ARKodeButcherTable_Free(B);
    if (flag >= 0)
        flag = ERKStepSStolerances(a->mem, a->o.rtol, a->o.atol);
    if (flag >= 0)
        flag = ERKStepSetMaxNumSteps(a->mem, a->o.max_steps);
    if (flag >= 0 && a->o.max_step > 0)
        flag = ERKStepSetMaxStep(a->mem, a->o.max_step);
    return check(a, flag, "ERKStep setup", err);
}

static bf_status create_imex(bf_ark1 *a, bf_err *err)
{
    if (a->o.order < 3 || a->o.order > 5)
        return bf_fail(err, BF_EINPUT, "ARKStep IMEX orders are 3, 4, 5");
    a->order = a->o.order;
    a->mem = ARKStepCreate(rhs_e, rhs_i, 0.0, a->y, a->sunctx);
    int flag = a->mem ? 0 : -1;
    if (flag >= 0)
        flag = ARKStepSetErrHandlerFn(a->mem, errh, a);
    if (flag >= 0)
        flag = ARKStepSetUserData(a->mem, a);
    if (flag >= 0)
        flag = ARKStepSetOrder(a->mem, a->o.order);
    if (flag >= 0)
        flag = ARKStepSStolerances(a->mem, a->o.rtol, a->o.atol);
    if (flag >= 0)
        flag = ARKStepSetMaxNumSteps(a->mem, a->o.max_steps);
    if (flag >= 0 && a->o.max_step > 0)
        flag = ARKStepSetMaxStep(a->mem, a->o.max_step);
    if (flag < 0)
        return check(a, flag, "ARKStep setup", err);
    const sunindextype b = (sunindextype)a->o.band;
    a->A = SUNBandMatrix((sunindextype)a->n, b, b, a->sunctx);
    a->LS = a->A ? SUNLinSol_Band(a->y, a->A, a->sunctx) : NULL;
    if (!a->A || !a->LS)
        return bf_fail(err, BF_EINTERNAL, "out of memory (band solver)");
    flag = ARKStepSetLinearSolver(a->mem, a->LS, a->A);
    return check(a, flag, "ARKStep linear solver setup", err);
}

static bf_status create_mri(bf_ark1 *a, bf_err *err)
{
    ARKodeButcherTable B = erk_table(a, err);
    if (!B)
        return err->status;
    /* the fast part: an adaptive explicit ARKStep, the inner stepper */
    a->inner = ARKStepCreate(rhs_i, NULL, 0.0, a->y, a->sunctx);
    int flag = a->inner ? 0 : -1;
    if (flag >= 0)
        flag = ARKStepSetErrHandlerFn(a->inner, errh, a);
    if (flag >= 0)
        flag = ARKStepSetUserData(a->inner, a);
    if (flag >= 0)
        flag = ARKStepSetTables(a->inner, B->q, B->p, NULL, B);
    ARKodeButcherTable_Free(B);
    if (flag >= 0)
        flag = ARKStepSStolerances(a->inner, a->o.rtol, a->o.atol);
    if (flag >= 0)
        flag = ARKStepSetMaxNumSteps(a->inner, a->o.max_steps);
    if (flag >= 0 && a->o.max_step > 0)
        flag = ARKStepSetMaxStep(a->inner, a->o.max_step);
    if (flag >= 0)
        flag = ARKStepCreateMRIStepInnerStepper(a->inner, &a->stepper);
    if (flag < 0)
        return check(a, flag, "the inner ARKStep's setup", err);
    a->mem = MRIStepCreate(rhs_e, NULL, 0.0, a->y, a->stepper, a->sunctx);
    flag = a->mem ? 0 : -1;
    if (flag >= 0)
        flag = MRIStepSetErrHandlerFn(a->mem, errh, a);
    if (flag >= 0)
        flag = MRIStepSetUserData(a->mem, a);
    if (flag >= 0)
        flag = MRIStepSetOrder(a->mem, a->o.order);
    if (flag >= 0)
        flag = MRIStepSetFixedStep(a->mem, a->o.slow_step);
    if (flag >= 0)
        flag = MRIStepSetMaxNumSteps(a->mem, a->o.max_steps);
    a->order = a->o.order;
    return check(a, flag, "MRIStep setup", err);
}

bf_status bf_ark1_create(bf_ark1 **out, size_t n, bf_rhs_fn fe, bf_rhs_fn fi,
                         void *ctx, const bf_ark1_opts *o, bf_err *err)
{
    *out = NULL;
    bf_ark1 *a = calloc(1, sizeof *a);
    if (!a)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    a->o = *o;
    a->steps_set = o->max_steps;
    a->n = n;
    a->fe = fe;
    a->fi = fi;
    a->ctx = ctx;
    bf_status st = BF_OK;
    if (SUNContext_Create(NULL, &a->sunctx))
        st = bf_fail(err, BF_EINTERNAL, "SUNContext_Create failed");
    if (!st && !(a->y = N_VNew_Serial((sunindextype)n, a->sunctx)))
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    if (!st) {
        N_VConst(0.0, a->y);
        st = o->kind == BF_ARK1_ERK    ? create_erk(a, err)
             : o->kind == BF_ARK1_IMEX ? create_imex(a, err)
                                       : create_mri(a, err);
    }
    if (st) {
        bf_ark1_free(a);
        return st;
    }
    *out = a;
    return BF_OK;
}

/* The calls of one evolve, per bf_ark1_kind. */
typedef struct stepper_fns {
    int (*init_step)(void *mem, realtype h);
    int (*reset)(void *mem, realtype t, N_Vector y);
    int (*stop_time)(void *mem, realtype t);
    int (*evolve)(void *mem, realtype tout, N_Vector y, realtype *tret,
                  int itask);
    int (*current_step)(void *mem, realtype *h);
    int (*max_num_steps)(void *mem, long mx);
} stepper_fns;

static const stepper_fns steppers[3] = {
    [BF_ARK1_ERK] = {ERKStepSetInitStep, ERKStepReset, ERKStepSetStopTime,
                     ERKStepEvolve, ERKStepGetCurrentStep,
                     ERKStepSetMaxNumSteps},
    [BF_ARK1_IMEX] = {ARKStepSetInitStep, ARKStepReset, ARKStepSetStopTime,
                      ARKStepEvolve, ARKStepGetCurrentStep,
                      ARKStepSetMaxNumSteps},
    [BF_ARK1_MRI] = {NULL, MRIStepReset, MRIStepSetStopTime, MRIStepEvolve,
                     NULL, NULL},
};

/* The internal steps a call from t to tend may take: max_steps per
 * budget_dt of its length (at least one budget_dt), or per call. */
static long steps_allowed(const bf_ark1 *a, double t, double tend)
{
    if (!(a->o.budget_dt > 0))
        return a->o.max_steps;
    double spans = ceil((tend - t) / a->o.budget_dt * (1.0 - 1e-12));
    double mx = (spans > 1.0 ? spans : 1.0) * (double)a->o.max_steps;
    return mx < 9e18 ? (long)mx : LONG_MAX;
}

/* MRI: new MRIStep and inner ARKStep memories, the counters so far kept
 * in base.  The inner ARKStep keeps state across the resets MRIStep makes
 * at every slow stage (its step count, on which its first-step growth
 * depends, and its controller's error history) that a checkpoint cannot
 * hold; made anew for every call, a run continued from a checkpoint
 * takes the same inner steps as the run that was not interrupted. */
static bf_status mri_renew(bf_ark1 *a, bf_err *err)
{
    bf_counters c;
    bf_ark1_counters(a, &c);
    a->base = c;
    MRIStepFree(&a->mem);
    MRIStepInnerStepper_Free(&a->stepper);
    ARKStepFree(&a->inner);
    return create_mri(a, err);
}

/* ------------------------------------------------------------ kinks */

static int root_cb(realtype t, N_Vector y, realtype *g, void *ud)
{
    bf_ark1 *a = ud;
    return a->g(a->ctx, t, N_VGetArrayPointer(y), g);
}

/* after every accepted step: its start and end */
static int post_cb(realtype t, N_Vector y, void *ud)
{
    bf_ark1 *a = ud;
    double *p = a->yprev;
    a->yprev = a->ycur;
    a->ycur = p;
    a->tprev = a->tcur;
    a->tcur = t;
    memcpy(a->ycur, N_VGetArrayPointer(y), a->n * sizeof *a->ycur);
    return 0;
}

static int roots_on(bf_ark1 *a, int on)
{
    int flag = ERKStepRootInit(a->mem, on ? a->ng : 0, on ? root_cb : NULL);
    if (flag >= 0 && on)
        flag = ERKStepSetNoInactiveRootWarn(a->mem);
    return flag;
}

bf_status bf_ark1_set_kinks(bf_ark1 *a, int n, bf_root1_fn g, bf_err *err)
{
    if (a->o.kind != BF_ARK1_ERK || n < 1)
        return bf_fail(err, BF_EINTERNAL, "kinks need the ERK kind and a "
                       "root function");
    a->g = g;
    a->ng = n;
    a->yprev = calloc(a->n, sizeof *a->yprev);
    a->ycur = calloc(a->n, sizeof *a->ycur);
    if (!a->yprev || !a->ycur)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    int flag = roots_on(a, 1);
    if (flag >= 0)
        flag = ERKStepSetPostprocessStepFn(a->mem, post_cb);
    return check(a, flag, "rootfinding setup", err);
}

/* A kink at tr inside the last step (tprev, tcur]: the state at tr is not
 * ARKODE's interpolant (whose error across a kink is not controlled) but
 * the integration again from the step's start to tr with tr as the stop
 * time and no rootfinding, steps that end on the kink instead of crossing
 * it; then ERKStep restarts at tr with the roots on. */
static int restart_at(bf_ark1 *a, double tr, double tend)
{
    double h = 0.0, tret = a->tprev;
    ERKStepGetCurrentStep(a->mem, &h);
    memcpy(N_VGetArrayPointer(a->y), a->yprev, a->n * sizeof(double));
    a->tcur = a->tprev;
    memcpy(a->ycur, a->yprev, a->n * sizeof(double));
    int flag = roots_on(a, 0);
    if (flag >= 0)
        flag = ERKStepSetInitStep(a->mem, h);
    if (flag >= 0)
        flag = ERKStepReset(a->mem, a->tprev, a->y);
    if (flag >= 0)
        flag = ERKStepSetStopTime(a->mem, tr);
    if (flag >= 0 && tr > a->tprev)
        flag = ERKStepEvolve(a->mem, tr, a->y, &tret, ARK_NORMAL);
    if (flag >= 0)
        flag = roots_on(a, 1);
    if (flag >= 0)
        flag = ERKStepReset(a->mem, tr, a->y);
    if (flag >= 0)
        flag = ERKStepSetStopTime(a->mem, tend);
    a->tcur = tr;
    memcpy(a->ycur, N_VGetArrayPointer(a->y), a->n * sizeof(double));
    a->restarts++;
    return flag;
}

unsigned long long bf_ark1_restarts(const bf_ark1 *a) { return a->restarts; }

/* A call ended by the stop flag counts as not made: the counters go back
 * to those at its start, so that a checkpoint written now holds those of
 * the run that was not interrupted at this step. */
static bf_status interrupted(bf_ark1 *a, const bf_counters *before, double t,
                             double tend, bf_err *err)
{
    bf_counters now;
    bf_ark1_counters(a, &now);
    a->base.steps -= now.steps - before->steps;
    a->base.evals -= now.evals - before->evals;
    a->base.rejected -= now.rejected - before->rejected;
    a->base.iterations -= now.iterations - before->iterations;
    return bf_fail(err, BF_INTERRUPTED,
                   "interrupted inside ARKODE's integration from t = %.9g s "
                   "to %.9g s (the state stays at t = %.9g s)",
                   t, tend, t);
}

bf_status bf_ark1_evolve(bf_ark1 *a, double t, double tend, double *y,
                         bf_err *err)
{
    if (a->o.kind == BF_ARK1_MRI) {
        bf_status st = mri_renew(a, err);
        if (st)
            return st;
    }
    bf_counters before;
    bf_ark1_counters(a, &before);
    double *yy = N_VGetArrayPointer(a->y);
    memcpy(yy, y, a->n * sizeof *yy);
    a->failed = 0;
    a->stopped = 0;
    a->msg[0] = '\0';
    /* the same calls for the three steppers (MRIStep's slow step is
     * fixed: no initial step to carry over) */
    const stepper_fns *S = &steppers[a->o.kind];
    double tret = t;
    int flag = S->init_step ? S->init_step(a->mem, a->h_next) : 0;
    if (flag >= 0)
        flag = S->reset(a->mem, t, a->y);
    if (flag >= 0)
        flag = S->stop_time(a->mem, tend);
    const long allowed = steps_allowed(a, t, tend);
    if (flag >= 0 && S->max_num_steps && allowed != a->steps_set &&
        (flag = S->max_num_steps(a->mem, allowed)) >= 0)
        a->steps_set = allowed;
    if (a->g) {
        a->tcur = t;
        memcpy(a->ycur, yy, a->n * sizeof *yy);
    }
    /* with kinks: a restart at each root (a root that keeps coming back,
     * 1e7 times in one call, is a failure) */
    long restarts = 0;
    while (flag >= 0) {
        flag = S->evolve(a->mem, tend, a->y, &tret, ARK_NORMAL);
        if (flag != ARK_ROOT_RETURN || tret >= tend)
            break;
        if (++restarts > 10000000) {
            flag = ARK_TOO_MUCH_WORK;
            break;
        }
        flag = restart_at(a, tret, tend);
    }
    if (flag == ARK_ROOT_RETURN)
        flag = ARK_SUCCESS;
    if (flag >= 0 && S->current_step)
        S->current_step(a->mem, &a->h_next);
    if (flag < 0 && a->stopped)
        return interrupted(a, &before, t, tend, err);
    if (flag == ARK_TOO_MUCH_WORK && restarts <= 10000000)
        return bf_fail(err, BF_ENOCONV,
                       "ARKODE took more than %ld internal steps between "
                       "t = %.9g s and %.9g s (%s = %ld%s); a larger "
                       "max_step or tolerance takes fewer",
                       allowed, t, tend,
                       a->o.max_steps_key ? a->o.max_steps_key : "max_steps",
                       a->o.max_steps,
                       a->o.budget_dt > 0 ? " per [scene] dt" : " per call");
    if (flag < 0) {
        bf_status code = a->failed               ? BF_EUNSTABLE
                         : flag == ARK_TOO_MUCH_WORK ? BF_ENOCONV
                                                     : BF_EUNSTABLE;
        return bf_fail(err, code,
                       "ARKODE failed between t = %.9g s and %.9g s: %s%s%s",
                       t, tend, flag_name(a, flag), a->msg[0] ? ": " : "",
                       a->msg);
    }
    if (tret != tend)
        return bf_fail(err, BF_EINTERNAL,
                       "ARKODE stopped at t = %.17g s instead of %.17g s",
                       tret, tend);
    memcpy(y, yy, a->n * sizeof *y);
    return BF_OK;
}

void bf_ark1_counters(const bf_ark1 *a, bf_counters *c)
{
    long steps = 0, nfe = 0, nfi = 0, ntf = 0, nni = 0, nls = 0;
    memset(c, 0, sizeof *c);
    switch (a->o.kind) {
    case BF_ARK1_ERK:
        ERKStepGetNumSteps(a->mem, &steps);
        ERKStepGetNumRhsEvals(a->mem, &nfe);
        ERKStepGetNumErrTestFails(a->mem, &ntf);
        break;
    case BF_ARK1_IMEX:
        ARKStepGetNumSteps(a->mem, &steps);
        ARKStepGetNumRhsEvals(a->mem, &nfe, &nfi);
        ARKStepGetNumErrTestFails(a->mem, &ntf);
        ARKStepGetNumNonlinSolvIters(a->mem, &nni);
        ARKStepGetNumLinRhsEvals(a->mem, &nls);
        break;
    default: {
        long nsi = 0, fast = 0, ffe = 0, ffi = 0;
        MRIStepGetNumSteps(a->mem, &steps);
        MRIStepGetNumRhsEvals(a->mem, &nfe, &nsi);
        ARKStepGetNumSteps(a->inner, &fast);
        ARKStepGetNumRhsEvals(a->inner, &ffe, &ffi);
        ARKStepGetNumErrTestFails(a->inner, &ntf);
        nfi = ffe + ffi + nsi;
        nni = fast;
        break;
    }
    }
    c->steps = a->base.steps + (unsigned long long)steps;
    c->evals = a->base.evals + (unsigned long long)(nfe + nfi + nls);
    c->rejected = a->base.rejected + (unsigned long long)ntf;
    c->iterations = a->base.iterations + (unsigned long long)nni;
}

int bf_ark1_order(const bf_ark1 *a) { return a->order; }

void bf_ark1_describe(const bf_ark1 *a, char *buf, size_t cap)
{
    const char *tab = bf_arkode_table_name(a->o.table);
    tab = tab ? tab + 7 : "?"; /* drop "ARKODE_" */
    if (a->o.kind == BF_ARK1_ERK)
        snprintf(buf, cap, "ERK %s%s rtol=%g atol=%g", tab,
                 a->padded ? " (padded)" : "", a->o.rtol, a->o.atol);
    else if (a->o.kind == BF_ARK1_IMEX)
        snprintf(buf, cap, "IMEX ARK order %d rtol=%g atol=%g", a->order,
                 a->o.rtol, a->o.atol);
    else
        snprintf(buf, cap, "MRI order %d slow step %g, fast ERK %s rtol=%g",
                 a->order, a->o.slow_step, tab, a->o.rtol);
    if (a->o.max_step > 0)
        snprintf(buf + strlen(buf), cap - strlen(buf), " hmax=%g",
                 a->o.max_step);
}

double bf_ark1_h_next(const bf_ark1 *a) { return a->h_next; }
void bf_ark1_set_h_next(bf_ark1 *a, double h) { a->h_next = h; }

static const bf_field count_fields[] = {
    BF_FIELD(bf_counters, steps, BF_F_ULL, "1"),
    BF_FIELD(bf_counters, evals, BF_F_ULL, "1"),
    BF_FIELD(bf_counters, rejected, BF_F_ULL, "1"),
    BF_FIELD(bf_counters, iterations, BF_F_ULL, "1"),
};

static void ark_names(const char *prefix, char *h, char *c, size_t cap)
{
    snprintf(h, cap, "%s.arkode_h_next", prefix);
    snprintf(c, cap, "%s.arkode_counts", prefix);
}

bf_status bf_ark1_save(const bf_ark1 *a, bf_ckpt *ck, const char *prefix,
                       bf_err *err)
{
    char h[160], c[160];
    ark_names(prefix, h, c, sizeof h);
    bf_counters n;
    bf_ark1_counters(a, &n);
    bf_status st = bf_ckpt_put_real(ck, h, a->h_next, err);
    return st ? st
              : bf_ckpt_put_fields(ck, c, count_fields,
                                   BF_NFIELDS(count_fields), &n, err);
}

bf_status bf_ark1_load(bf_ark1 *a, const bf_ckpt *ck, const char *prefix,
                       bf_err *err)
{
    char h[160], c[160];
    ark_names(prefix, h, c, sizeof h);
    bf_counters n = {0};
    bf_status st = bf_ckpt_get_real(ck, h, &a->h_next, err);
    if (!st)
        st = bf_ckpt_get_fields(ck, c, count_fields, BF_NFIELDS(count_fields),
                                &n, err);
    if (!st) {
        /* what this integrator counted since its creation is not in the
         * saved run's counts */
        bf_counters now;
        a->base = (bf_counters){0};
        bf_ark1_counters(a, &now);
        a->base.steps = n.steps - now.steps;
        a->base.evals = n.evals - now.evals;
        a->base.rejected = n.rejected - now.rejected;
        a->base.iterations = n.iterations - now.iterations;
    }
    return st;
}
