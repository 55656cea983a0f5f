/* ballsys_events.c: the event splitting of the ball system's steps at
 * contact onsets and releases ([integrator] events = yes; ballsys.h,
 * docs/accuracy-balls.md, docs/forces.md). */
#include "models/ballsys.h"

#include "diag/hermite.h"
#include "effects/effect_kernels.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- Event splitting ([integrator] events = yes).
 *
 * The Hertz force k x^{3/2} is C^1 but not C^2 where a contact begins or
 * ends (x = 0), so a step of a fixed-step method that straddles an onset
 * or a release loses the method's order there.  The overlap along a step
 * is the gap: g_floor,i = x_i - R_i, g_pair,i = (x_{i+1} - x_i) - (R_i +
 * R_{i+1}) (computed as the force kernels test them, so the sign of a gap
 * is exactly whether that force acts).  After the step, a gap whose sign
 * differs at its ends had an onset or a release inside it.  Then the step
 * is re-taken from its saved start as a substep of theta dt, theta in
 * (0, 1), and theta is adjusted (regula falsi, Illinois variant: the
 * retained end's value is halved when the same end is kept twice, which
 * keeps the convergence superlinear, started from the root of the cubic
 * Hermite interpolant of the gap and its rate at both ends) until the
 * substep ends on the gap's zero to round-off (4 ulps of the positions
 * involved) or theta is known to 4 ulps; the substep kept is the one on
 * the far side of the zero (or on it), so the next piece starts where
 * the new force law holds.  If another gap crossed inside the kept
 * substep, its own zero, earlier, is located the same way.  The rest of
 * the step is then taken the same way (it may hold further events), at
 * most MAX_PIECES pieces per step.
 *
 * The contract of bf_ballsys_step is kept: one call goes from t to
 * t + dt; count.evals counts every evaluation (the trials of the root
 * finder included), count.steps the pieces kept, count.rejected the
 * trial substeps thrown away.  Analyses observe whole steps (their hooks
 * are around the call).  The force cache is keyed by positions, so a
 * re-taken substep never reuses a stale force.  Off (the default), no
 * code here runs and every result is as before.
 *
 * Releases.  A damped contact's force f = max(0, u), with u the sum of
 * the elastic and damping terms (damped.c, eq. 1), is continuous where u
 * falls to 0 while the bodies still overlap, but its derivative jumps
 * there: a step across it makes a local velocity error O(dt^2), whatever
 * the method's order.  Each damped contact (the floor under each ball,
 * each pair) therefore adds the event u(x, v), located like a gap after
 * the gaps (its zero first guessed linearly: its rate needs the
 * acceleration).  And each piece integrates one smooth force: the
 * contact's branch (bf_floor.branch, bf_contact.branch) is set at the
 * piece's start from the side of u there, for all its stages and trials:
 * u itself while it pushes (also a stage beyond the zero, where u < 0:
 * the smooth continuation the root finder needs), 0 once released (until
 * the bodies part or u turns positive again, located as well), and the
 * maximum where u is 0 at the start (outside the contact).  The branches
 * are the maximum again between steps, so that any evaluation outside a
 * step sees the clipped force.  A branch that changes at a located event
 * bumps the force epoch: the force cached at the piece's start (the root
 * finder's last trial, on the old branch) is not the new piece's.
 *
 * Two events at the same instant (mirror-symmetric impacts: bit-identical
 * gaps) are located once: an event already at its zero to round-off where
 * another was located is left to the next piece's start_sides, and the
 * search for an earlier crossing stops after m + 1 locations. */
enum { MAX_PIECES = 100000, MAX_TRIALS = 60 };

/* which gaps the effects make (every ball system: the coupled model's
 * whole-system ARKODE restarts at them too) */
void bf_ballsys_gaps_setup(bf_ballsys *s)
{
    const size_t n = s->b.n;
    for (size_t k = 0; k < s->neff; k++) {
        const bf_effect_kernel kk = bf_effect_kernel_of(s->eff[k].type);
        s->gap_floor |= kk == BF_KERNEL_FLOOR;
        s->gap_pair |= kk == BF_KERNEL_CONTACT && n > 1;
        if (kk == BF_KERNEL_FLOOR)
            s->floor = s->eff[k].self;
        if (kk == BF_KERNEL_CONTACT)
            s->contact = s->eff[k].self;
        /* the force's exponent at an onset (graded_h): delta^{3/2}
         * elastic, delta^{1/2} viscous, delta^{1/4} with restitution */
        if (kk == BF_KERNEL_FLOOR || kk == BF_KERNEL_CONTACT) {
            const bf_floor *f = s->eff[k].self;
            const bf_contact *c = s->eff[k].self;
            const int fl = kk == BF_KERNEL_FLOOR;
            const double kink = !((fl ? f->law : c->law) & BF_LAW_DAMPED)
                                    ? 1.5
                                : (fl ? f->e : c->e) < 1 ? 0.25
                                                         : 0.5;
            if (!(s->kink_power > 0) || kink < s->kink_power)
                s->kink_power = kink;
        }
    }
    s->ngaps = (s->gap_floor ? (int)n : 0) + (s->gap_pair ? (int)n - 1 : 0);
    s->rel_floor = s->floor && (s->floor->law & BF_LAW_DAMPED);
    s->rel_pair = s->gap_pair && s->contact &&
                  (s->contact->law & BF_LAW_DAMPED);
    s->nrel = (s->rel_floor ? (int)n : 0) + (s->rel_pair ? (int)n - 1 : 0);
}

bf_status bf_ballsys_events_setup(bf_ballsys *s, bf_err *err)
{
    const size_t n = s->ode.n; /* the balls, and the work (nw) */
    const size_t m = (size_t)(s->ngaps + s->nrel);
    s->ev_work = calloc(6 * n + 4 * m + 1, sizeof *s->ev_work);
    s->ev_side = calloc(m + 1, sizeof *s->ev_side);
    s->branch = calloc((size_t)s->nrel + 1, sizeof *s->branch);
    if (!s->ev_work || !s->ev_side || !s->branch)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    if (s->it->type->flags & BF_INT_ADAPTIVE) {
        /* the integrator stops and restarts at each zero itself */
        s->kinks = (bf_events){s->ngaps, bf_ballsys_gaps_fn, NULL, NULL, s};
        bf_integrator_set_kinks(s->it, &s->kinks);
        return BF_OK;
    }
    s->split = s->ngaps > 0;
    if (s->split)
        s->fast_advance = NULL; /* runs go step by step, through the split */
    /* the damped contacts take their branches from here (the effects'
     * states are this system's: a lent effect is never a floor or a
     * contact) */
    if (s->split && s->rel_floor)
        ((bf_floor *)s->floor)->branch = s->branch;
    if (s->split && s->rel_pair)
        ((bf_contact *)s->contact)->branch =
            s->branch + (s->rel_floor ? s->b.n : 0);
    return BF_OK;
}

/* the gaps at (t, x) (cm) and, with v, their rates (cm/s); a driven
 * floor's gap is x - R - h(t) */
static void gaps(const bf_ballsys *s, double t, const double *x,
                 const double *v, double *g, double *rate)
{
    const double *R = s->b.R;
    int m = 0;
    double h = 0, hd = 0;
    const int driven = s->floor && (s->floor->law & BF_LAW_DRIVEN);
    if (driven)
        bf_floor_height(s->floor, t, &h, &hd);
    if (s->gap_floor)
        for (size_t i = 0; i < s->b.n; i++, m++) {
            g[m] = driven ? x[i] - R[i] - h : x[i] - R[i];
            if (rate)
                rate[m] = driven ? v[i] - hd : v[i];
        }
    if (s->gap_pair)
        for (size_t i = 0; i + 1 < s->b.n; i++, m++) {
            g[m] = (x[i + 1] - x[i]) - (R[i] + R[i + 1]);
            if (rate)
                rate[m] = v[i + 1] - v[i];
        }
}

/* round-off of gap j at x: 4 ulps of what it is formed from */
static double gap_tol(const bf_ballsys *s, const double *x, int j)
{
    const size_t n = s->b.n;
    const double *R = s->b.R;
    size_t i = (size_t)j;
    if (s->gap_floor && i < n)
        return 4 * DBL_EPSILON * (fabs(x[i]) + R[i]);
    if (s->gap_floor)
        i -= n;
    return 4 * DBL_EPSILON *
           (fabs(x[i]) + fabs(x[i + 1]) + R[i] + R[i + 1]);
}

int bf_ballsys_gaps_fn(void *ctx, double t, const double *x, const double *v,
                       double *g)
{
    gaps(ctx, t, x, v, g, NULL);
    return 0;
}

/* release event c (dyn): the unclipped force of the floor on ball c, or
 * of pair c - n (after the floor's), with the floor at h moving at hd;
 * *scale: the magnitudes it sums */
static double release(const bf_ballsys *s, double h, double hd, int c,
                      const double *x, const double *v, double *scale)
{
    size_t i = (size_t)c;
    if (s->rel_floor && i < s->b.n)
        return bf_floor_unclipped(s->floor, &s->b, h, hd, i, x, v, scale);
    if (s->rel_floor)
        i -= s->b.n;
    return bf_contact_unclipped(s->contact, &s->b, i, x, v, scale);
}

static void floor_at(const bf_ballsys *s, double t, double *h, double *hd)
{
    *h = *hd = 0.0;
    if (s->floor)
        bf_floor_height(s->floor, t, h, hd);
}

/* the events at (t, x, v): the gaps (with rate, their rates), then the
 * releases */
static void events(const bf_ballsys *s, double t, const double *x,
                   const double *v, double *g, double *rate)
{
    gaps(s, t, x, v, g, rate);
    if (!s->nrel)
        return;
    double h, hd, scale;
    floor_at(s, t, &h, &hd);
    for (int c = 0; c < s->nrel; c++)
        g[s->ngaps + c] = release(s, h, hd, c, x, v, &scale);
}

/* round-off of event j at (t, x, v): 4 ulps of what it is formed from */
static double event_tol(const bf_ballsys *s, double t, const double *x,
                        const double *v, int j)
{
    if (j < s->ngaps)
        return gap_tol(s, x, j);
    double h, hd, scale;
    floor_at(s, t, &h, &hd);
    release(s, h, hd, j - s->ngaps, x, v, &scale);
    return 4 * DBL_EPSILON * scale;
}

static int side(double g) { return (g > 0) - (g < 0); }

/* The sides of the events at a piece's start.  A gap exactly 0 there (a
 * contact that begins or ends on a step's boundary) takes the side it
 * moves to, so that the substeps after such an onset are graded too. */
static void start_sides(const bf_ballsys *s, const double *g,
                        const double *rate, size_t m, int *sa)
{
    for (size_t k = 0; k < m; k++) {
        sa[k] = side(g[k]);
        if (!sa[k] && (int)k < s->ngaps)
            sa[k] = side(rate[k]);
    }
}

/* each damped contact's branch for the piece whose events start on the
 * sides sa: free where its gap starts open (a stage past the onset of
 * that piece must not feel the force: delta^{1/4} is far from smooth
 * there), else the side of its release event (BF_BRANCH_PUSH, _FREE,
 * _CLIP are +1, -1, 0); NULL: the maximum (between steps) */
static int set_branches(bf_ballsys *s, const int *sa)
{
    const int n = (int)s->b.n;
    int changed = 0;
    for (int c = 0; c < s->nrel; c++) {
        const int gap = s->rel_floor && c < n ? c
                        : (s->gap_floor ? n : 0) + c - (s->rel_floor ? n : 0);
        const signed char b = (signed char)(!sa ? BF_BRANCH_CLIP
                                            : sa[gap] > 0 ? BF_BRANCH_FREE
                                                          : sa[s->ngaps + c]);
        changed |= b != s->branch[c];
        s->branch[c] = b;
    }
    return changed;
}

/* the integrator's step (specialised or generic), without splitting */
static bf_status plain_step(bf_ballsys *s, double t, double dt, bf_err *err)
{
    if (s->fast_step && s->ode.accel == bf_ballsys_accel)
        return s->fast_step(s->it, &s->ode, &s->forces, t, dt, err);
    return bf_ballsys_step_generic(s, t, dt, err);
}

/* a substep of h from (xa, va) at ta; the result in s->b */
static bf_status substep(bf_ballsys *s, const double *xa, const double *va,
                         double ta, double h, bf_err *err)
{
    memcpy(s->b.x, xa, s->ode.n * sizeof *xa);
    memcpy(s->b.v, va, s->ode.n * sizeof *va);
    return plain_step(s, ta, h, err);
}

/* root in (0, 1) of the cubic Hermite interpolant of g (values g0, g1,
 * derivatives d0, d1 per unit theta), by bisection (no force evaluation) */
static double hermite_root(double g0, double g1, double d0, double d1)
{
    double lo = 0, hi = 1;
    for (int k = 0; k < 40; k++) {
        double th = 0.5 * (lo + hi);
        double h = bf_hermite(th, 1.0, g0, d0, g1, d1);
        if (side(h) == side(g0))
            lo = th;
        else
            hi = th;
    }
    return 0.5 * (lo + hi);
}

typedef struct piece_ws {
    double *xa, *va, *xh, *vh, *ga, *gb, *ra, *rb;
    double ta, h; /* the piece: from ta over h */
    unsigned trials;
} piece_ws;

/* Locate the zero of event j (a gap or a release) in the piece: on
 * return (xh, vh) is the state after the substep theta h (*theta), on the
 * far side of the zero or on it; on entry (xh, vh) is that after
 * theta_hi h with event value ghi (far side) and glo its value at the
 * piece's start (near side). */
static bf_status locate(bf_ballsys *s, piece_ws *w, int j, double thhi,
                        double ghi, double glo, double guess, double *theta,
                        bf_err *err)
{
    const size_t n = s->ode.n;
    const int far = side(ghi);
    double lo = 0, hi = thhi, flo = glo, fhi = ghi, th = guess * thhi;
    int kept = 0; /* last end kept: -1 lo, +1 hi */
    double *g = w->gb;
    for (int it = 0; it < MAX_TRIALS; it++) {
        if (!(th > lo && th < hi))
            th = 0.5 * (lo + hi);
        bf_status st = substep(s, w->xa, w->va, w->ta, th * w->h, err);
        w->trials++;
        if (st)
            return st;
        events(s, w->ta + th * w->h, s->b.x, s->b.v, g, NULL);
        const double f = g[j];
        if (f == 0 || side(f) == far) {
            hi = th;
            fhi = f;
            memcpy(w->xh, s->b.x, n * sizeof *w->xh);
            memcpy(w->vh, s->b.v, n * sizeof *w->vh);
            if (kept == 1)
                flo *= 0.5;
            kept = 1;
        } else {
            lo = th;
            flo = f;
            if (kept == -1)
                fhi *= 0.5;
            kept = -1;
        }
        if (fhi == 0 ||
            fabs(fhi) <= event_tol(s, w->ta + hi * w->h, w->xh, w->vh, j) ||
            hi - lo <= 4 * DBL_EPSILON * hi)
            break;
        th = (lo * fhi - hi * flo) / (fhi - flo);
    }
    *theta = hi;
    return BF_OK;
}

/* Graded substeps inside a contact.  Splitting alone does not give the
 * nominal orders back: inside a contact, s seconds after its onset (or
 * before its release), the deformation is about |g'| s and the force
 * about k (|g'| s)^{3/2}, whose second derivative grows like s^{-1/2}.  A
 * step of size h at distance s from the kink makes a local error
 * ~ A h^{p+1} s^{3/2-p} (order p, A = k |g'|^{3/2}/m), so with uniform
 * steps the first few after the onset give A h^{5/2} and the global order
 * is 5/2 whatever p is (measured: RK4 1.9-2.5 with splitting alone).  The
 * cure is the graded mesh of singular quadrature: nodes s_k = S (k/K)^gam,
 * K = S/dt, over a zone of length S (events_zone) at both ends of each
 * contact; their errors sum to A S^{5/2} K^{-p} (order p) when
 * gam >= (p + 1)/(5/2), and they cost the same K substeps as uniform
 * steps over the zone.  The distance to the kink is estimated from each
 * gap in contact as s = |g|/|g'| (exact to first order at both ends;
 * large at maximum compression, where the steps are dt); the substep is
 *   h = max(S (dt/S)^gam, gam dt (s/S)^{1 - 1/gam})   (at most dt),
 * the first node being the lower bound. */
static double graded_h(const bf_ballsys *s, const double *g,
                       const double *rate, const int *side_of, double dt)
{
    const double S = s->it->split_zone,
                 gam = (bf_integrator_order(s->it) + 1) / (1 + s->kink_power);
    if (!(gam > 1) || !(dt < S))
        return dt;
    double dist = INFINITY;
    for (int j = 0; j < s->ngaps; j++)
        if (side_of[j] < 0 && rate[j] != 0) /* in contact (a located
                                                 * onset: g = 0, side -1) */
            dist = fmin(dist, fabs(g[j]) / fabs(rate[j]));
    if (!(dist < S))
        return dt;
    double h = gam * dt * pow(dist / S, 1 - 1 / gam);
    return fmin(dt, fmax(h, S * pow(dt / S, gam)));
}

bf_status bf_ballsys_step_split(bf_ballsys *s, double t, double dt,
                                bf_err *err)
{
    const size_t n = s->ode.n, m = (size_t)(s->ngaps + s->nrel);
    double *x0 = s->ev_work, *v0 = x0 + n;
    piece_ws w = {.xa = x0 + 2 * n, .va = x0 + 3 * n, .xh = x0 + 4 * n,
                  .vh = x0 + 5 * n, .ga = x0 + 6 * n, .gb = x0 + 6 * n + m,
                  .ra = x0 + 6 * n + 2 * m, .rb = x0 + 6 * n + 3 * m,
                  .ta = t};
    int *sa = s->ev_side;
    const bf_counters c0 = s->it->count;
    memcpy(x0, s->b.x, n * sizeof *x0);
    memcpy(v0, s->b.v, n * sizeof *v0);
    memcpy(w.xa, x0, n * sizeof *x0);
    memcpy(w.va, v0, n * sizeof *v0);
    events(s, w.ta, w.xa, w.va, w.ga, w.ra);
    start_sides(s, w.ga, w.ra, m, sa);
    set_branches(s, sa);
    unsigned pieces = 0;
    double rest = dt; /* of the step, from w.ta */
    bf_status st = BF_OK;
    for (;;) {
        const double hg = graded_h(s, w.ga, w.ra, sa, dt);
        w.h = hg < rest ? hg : rest;
        st = substep(s, w.xa, w.va, w.ta, w.h, err);
        w.trials++;
        if (st)
            break;
        pieces++;
        events(s, w.ta + w.h, s->b.x, s->b.v, w.gb, w.rb);
        /* the crossing that the Hermite interpolants (linear ones for
         * the releases) put first */
        int j = -1;
        double first = 2, th = 1;
        for (size_t k = 0; k < m; k++) {
            if (sa[k] * side(w.gb[k]) >= 0)
                continue;
            double r = (int)k >= s->ngaps
                           ? w.ga[k] / (w.ga[k] - w.gb[k])
                           : hermite_root(w.ga[k], w.gb[k], w.h * w.ra[k],
                                          w.h * w.rb[k]);
            if (r < first) {
                first = r;
                j = (int)k;
            }
        }
        if (pieces >= MAX_PIECES) {
            /* (a safety net: a step that ends before t + dt is a failure,
             * never a silent success) */
            st = bf_fail(err, BF_EUNSTABLE, "more than %d event pieces in "
                         "one step at t = %.9g s (contacts chattering: a "
                         "smaller [scene] dt)", (int)MAX_PIECES, t);
            break;
        }
        if (j >= 0) {
            memcpy(w.xh, s->b.x, n * sizeof *w.xh);
            memcpy(w.vh, s->b.v, n * sizeof *w.vh);
            double ghi = w.gb[j], guess = first;
            for (size_t pass = 0;; pass++) {
                if ((st = locate(s, &w, j, th, ghi, w.ga[j], guess, &th,
                                 err)))
                    break;
                /* did another event cross before? (its zero comes
                 * first; one at its zero here is simultaneous) */
                const double tz = w.ta + th * w.h;
                events(s, tz, w.xh, w.vh, w.gb, NULL);
                int k2 = -1;
                for (size_t k = 0; k < m; k++)
                    if ((int)k != j && sa[k] * side(w.gb[k]) < 0 &&
                        fabs(w.gb[k]) > event_tol(s, tz, w.xh, w.vh, (int)k))
                        k2 = (int)k;
                if (k2 < 0)
                    break;
                if (pass > m) {
                    st = bf_fail(err, BF_EUNSTABLE, "the contact events "
                                 "at t = %.9g s could not be ordered (%zu "
                                 "locations)", tz, pass);
                    break;
                }
                j = k2;
                ghi = w.gb[j];
                guess = 0.5;
            }
            if (st)
                break;
            memcpy(s->b.x, w.xh, n * sizeof *w.xh);
            memcpy(s->b.v, w.vh, n * sizeof *w.vh);
        } else if (w.h == rest) {
            break; /* the piece ends the step */
        }
        /* the next piece starts here; at a located zero, on the new side
         * of gap j */
        const int far = j < 0 ? 0 : side(w.gb[j]) ? side(w.gb[j]) : -sa[j];
        memcpy(w.xa, s->b.x, n * sizeof *w.xa);
        memcpy(w.va, s->b.v, n * sizeof *w.va);
        w.ta += th * w.h;
        rest -= th * w.h;
        events(s, w.ta, w.xa, w.va, w.ga, w.ra);
        start_sides(s, w.ga, w.ra, m, sa);
        if (j >= 0)
            sa[j] = far;
        if (set_branches(s, sa))
            s->ode.epoch++;
        if (!(rest > 0))
            break;
    }
    set_branches(s, NULL);
    if (st) {
        memcpy(s->b.x, x0, n * sizeof *x0);
        memcpy(s->b.v, v0, n * sizeof *v0);
        return st;
    }
    s->it->count.steps = c0.steps + pieces;
    s->it->count.rejected = c0.rejected + (w.trials - pieces);
    return BF_OK;
}

/* A twin (the shadow of a Lyapunov estimate) without splitting takes the
 * integrator's step through the ode, the same bits as the system's own
 * step (specialised or generic, ball_steps.h).  With splitting it must
 * find its own events: split at the system's, or not at all, each of its
 * impacts would be integrated across the kink of the force and the
 * separation of the two trajectories would jump by the step's O(1)
 * local error there instead of growing with the dynamics.  So the
 * system's trajectory is swapped for the twin's (state, integrator, the
 * time of the integrator's cached force) for one split step.  The
 * scratch and the contacts' branches are the step's own (both are set
 * up afresh by each step), and the force epoch is shared: a bump by
 * either only makes the other's cache miss (a re-evaluation, same
 * bits). */
bf_status bf_ballsys_step_twin(void *ctx, bf_ball_twin *tw, double t,
                               double dt, bf_err *err)
{
    bf_ballsys *s = ctx;
    if (!s->split)
        return bf_integrator_step(tw->it, &s->ode, t, dt, tw->x, tw->v, err);
    double *const x = s->b.x, *const v = s->b.v;
    bf_integrator *const it = s->it;
    const double t_cached = s->t_cached;
    s->b.x = tw->x;
    s->b.v = tw->v;
    s->it = tw->it;
    s->t_cached = tw->t_cached;
    bf_status st = bf_ballsys_step_split(s, t, dt, err);
    tw->t_cached = s->t_cached;
    s->b.x = x;
    s->b.v = v;
    s->it = it;
    s->t_cached = t_cached;
    return st;
}
