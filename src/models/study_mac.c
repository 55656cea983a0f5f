/* study_mac.c: the convergence study of the MAC solver (model mac) in dt:
 * a SELF-CONVERGENCE study.  Methods are [mac] update variants (printed,
 * consistent, original) with their [mac] keys; compared are the face
 * velocities u [(ni+1) nj] and v [ni (nj+1)] (the thesis's scaled units,
 * W); no invariant.
 *
 * Why no ARKODE reference: the scheme is a projection method, its
 * pressure solve a constraint (div w = 0 in the full cells), not part of
 * an ODE that ARKODE could integrate.  The reference is therefore the
 * compared method itself at a much smaller step, [scene] dt / 64, its
 * estimated error the difference to the run at [scene] dt / 128
 * (study.h, self_reference): what converge then reports is the observed
 * order in dt of the scheme and its distance from its own dt -> 0 limit,
 * not its error against the equations.  One method at a time (each is
 * its own reference).
 *
 * The limit exists only where nothing switches with dt: the reservoir
 * with [mac] inflow = copy (U(2,J) = U(3,J), P = P0) has none (the
 * differences between dt and dt/2 stop shrinking below dt = 0.00625,
 * largest at the IN columns; bench/mac_dt_differences.py), with inflow =
 * prescribed it converges at first order; markers crossing cells and
 * changing flags are events too.  The notes say so. */
#include <stdio.h>
#include <string.h>

#include "mac/mac.h"
#include "models/mac_model.h"
#include "models/studies.h"

static int mac_adaptive(const bf_model_setup *s)
{
    (void)s;
    return 0;
}

static bf_status mac_reference(const bf_model_setup *s,
                               const bf_study_methods *o, char *method,
                               size_t cap, bf_err *err)
{
    (void)s;
    if (o->n != 1)
        return bf_fail(err, BF_EINPUT, "the mac study is a self-convergence "
                       "study (its reference is the compared method at a "
                       "small dt): give one method, not %zu", o->n);
    snprintf(method, cap, "%s", o->methods[0]);
    return BF_OK;
}

static void mac_view(void *self, bf_study_view *v)
{
    const bf_mac *m = bf_mac_model_solver(self);
    int ni, nj;
    bf_mac_dims(m, &ni, &nj, NULL, NULL);
    memset(v, 0, sizeof *v);
    v->ngroups = 2;
    v->g[0].name = "u";
    v->g[0].unit = "W";
    v->g[0].a = bf_mac_u(m);
    v->g[0].n = (size_t)(ni + 1) * (size_t)nj;
    v->g[1].name = "v";
    v->g[1].unit = "W";
    v->g[1].a = bf_mac_v(m);
    v->g[1].n = (size_t)ni * (size_t)(nj + 1);
}

static void mac_notes(const bf_model_setup *s, char *buf, size_t cap)
{
    const bf_mac_params *k = bf_setup_get(s, &bf_mac_spec, NULL);
    size_t l = strlen(buf);
    snprintf(buf + l, cap - l,
             "note: SELF-CONVERGENCE: the MAC scheme's pressure solve is a "
             "constraint, so there is no ARKODE reference; the reference is "
             "the compared method itself at [scene] dt / 64 (its estimated "
             "error: the difference to dt / 128).  The errors are distances "
             "from the scheme's own limit dt -> 0, not errors against the "
             "equations.\n");
    if (k && k->problem == BF_MAC_RESERVOIR && !k->inflow_prescribed) {
        l = strlen(buf);
        snprintf(buf + l, cap - l,
                 "note: the reservoir with [mac] inflow = copy has no limit "
                 "dt -> 0 (the differences stop shrinking below dt = "
                 "0.00625); --set mac.inflow=prescribed has one.\n");
    }
}

const bf_study_type bf_study_mac = {
    .method_key = "mac.update",
    .param_section = "mac",
    .invariant = "none",
    .default_ref_rtol = 1e-12,
    .max_ref_rtol = 1.0,
    .self_reference = 64,
    .adaptive = mac_adaptive,
    .reference = mac_reference,
    .view = mac_view,
    .describe = bf_mac_model_describe,
    .notes = mac_notes,
};
