/* study_g72.c: the convergence study of Greenspan's 1972 two-fluid
 * particles (model greenspan72): methods are [greenspan72] integrators
 * (leapfrog, the paper's scheme, eqs 2.1-2.4; arkode) with their
 * [greenspan72] keys; compared are the positions (x, y; cm) of the
 * particles.  Not the velocities: the leapfrog carries v^{k-1/2}, half a
 * step behind the positions (the model's output says so), which against
 * a reference's v(t_k) is an O(dt) difference of convention, not an
 * error of the scheme.  The model has no energy (support-set gravity has
 * no potential), so there is no invariant.
 *
 * The reference: ARKODE's adaptive ERK on the particles' ODE (g72_ode.h,
 * the limit dt -> 0 of the leapfrog, with the model's own forces) at a
 * tight tolerance, VERNER_8_5_6, else DORMAND_PRINCE_7_4_5, else
 * CASH_KARP_6_4_5 when compared.
 *
 * The ODE is not smooth: the support-set gravity g_j (eqs 2.8, 2.9)
 * jumps when a particle changes band or a band under it empties, the
 * areas have kinks, the repulsion's beta factor a kink at r = d, and the
 * walls reflect (eq. 2.13).  Across such an event a fixed-step method
 * loses its order (a jump of g costs O(dt) in the velocity, O(dt^2) in
 * a position per event) and the adaptive reference its estimated
 * accuracy; and the flow is chaotic, so errors grow like exp(lambda T).
 * The orders mean something only on a short window in which no event
 * happens; the notes say so. */
#include <stdio.h>
#include <string.h>

#include "models/greenspan.h"
#include "models/studies.h"

static void g72_view(void *self, bf_study_view *v)
{
    bf_study_particles_view(bf_greenspan72_particles(self), 0, v);
}

static void g72_notes(const bf_model_setup *s, char *buf, size_t cap)
{
    (void)s;
    size_t l = strlen(buf);
    snprintf(buf + l, cap - l,
             "note: the reference is ARKODE on the particles' ODE (the "
             "leapfrog's limit dt -> 0, the same forces).  That ODE is not "
             "smooth: the support-set gravity jumps when a particle changes "
             "band or a band below it empties, and the walls reflect; "
             "across such an event the orders degrade (and the flow is "
             "chaotic), so compare over a short window (--t-end) without "
             "events.  Compared are positions only: the leapfrog's "
             "velocities are half a step behind.\n");
}

const bf_study_type bf_study_greenspan72 = {
    .method_key = "greenspan72.integrator",
    .param_section = "greenspan72",
    .invariant = "none",
    .default_ref_rtol = 1e-12,
    .max_ref_rtol = 1e-10,
    .adaptive = bf_greenspan72_adaptive,
    .reference = bf_study_arkode_erk,
    .view = g72_view,
    .describe = bf_greenspan72_describe,
    .notes = g72_notes,
};
