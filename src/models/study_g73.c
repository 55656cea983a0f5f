/* study_g73.c: the convergence study of Greenspan's 1973 particles
 * (model greenspan73): methods are [greenspan73] integrators (greenspan73,
 * the paper's implicit scheme; leapfrog, the 1972 leapfrog; arkode) with
 * their [greenspan73] keys; compared are the positions (x, y; cm) and the
 * velocities (vx, vy; cm/s) of the particles; the invariant is the energy
 * K + V (eq. 2.17 and gravity).
 *
 * The reference: ARKODE's adaptive ERK on the particles' ODE (the limit
 * dt -> 0 of the scheme, g73_ode.h) at a tight tolerance, VERNER_8_5_6,
 * else DORMAND_PRINCE_7_4_5, else CASH_KARP_6_4_5 when compared.  The
 * flows are chaotic (the hexagon's 34 particles): nearby trajectories
 * separate exponentially, so the errors at T grow like exp(lambda T) and
 * the comparison is meaningful for a short window only, as long as the
 * errors stay small against the particle spacing; the notes say so. */
#include <stdio.h>
#include <string.h>

#include "models/greenspan.h"
#include "models/studies.h"

static void g73_view(void *self, bf_study_view *v)
{
    bf_study_particles_view(bf_greenspan73_particles(self), 1, v);
}

static void g73_notes(const bf_model_setup *s, char *buf, size_t cap)
{
    (void)s;
    size_t l = strlen(buf);
    snprintf(buf + l, cap - l,
             "note: the reference is ARKODE on the particles' ODE (the "
             "scheme's limit dt -> 0).  Particle flows are chaotic: errors "
             "grow exponentially with T, so compare over a short window "
             "(--t-end), while the errors stay far below the particle "
             "spacing.\n");
}

const bf_study_type bf_study_greenspan73 = {
    .method_key = "greenspan73.integrator",
    .param_section = "greenspan73",
    .invariant = "energy",
    .default_ref_rtol = 1e-12,
    .max_ref_rtol = 1e-10,
    .adaptive = bf_greenspan73_adaptive,
    .reference = bf_study_arkode_erk,
    .view = g73_view,
    .describe = bf_greenspan73_describe,
    .notes = g73_notes,
};
