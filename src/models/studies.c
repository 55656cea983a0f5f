/* studies.c: what the convergence studies of the models share
 * (studies.h). */
#include <stdio.h>
#include <string.h>

#include "integrators/arkode.h"
#include "models/studies.h"

void bf_study_particles_view(const bf_particles *p, int velocities,
                             bf_study_view *v)
{
    memset(v, 0, sizeof *v);
    v->ngroups = velocities ? 2 : 1;
    v->g[0].name = "x";
    v->g[0].unit = "cm";
    v->g[0].a = p->x;
    v->g[0].b = p->y;
    v->g[0].n = p->n;
    if (velocities) {
        v->g[1].name = "v";
        v->g[1].unit = "cm/s";
        v->g[1].a = p->vx;
        v->g[1].b = p->vy;
        v->g[1].n = p->n;
    }
}

/* Does method string m use the table? */
static int uses_table(const char *m, const char *const *names,
                      const char *const *defaults, const char *table)
{
    size_t len = strcspn(m, ":");
    for (size_t k = 0; names[k]; k++) {
        if (strlen(names[k]) != len || strncmp(m, names[k], len))
            continue;
        const char *t = strstr(m, "table=");
        if (t)
            return !strncmp(t + 6, table, strlen(table)) &&
                   (t[6 + strlen(table)] == '\0' ||
                    t[6 + strlen(table)] == ':');
        return defaults[k] && !strcmp(defaults[k], table);
    }
    return 0;
}

bf_status bf_study_pick_table(const bf_study_methods *o,
                              const char *const *names,
                              const char *const *defaults,
                              const char *const *candidates, size_t ncand,
                              const char **table, bf_err *err)
{
    const char *t = o->ref_table;
    for (size_t k = 0; !t && k < ncand; k++) {
        int used = 0;
        for (size_t m = 0; m < o->n && !o->ref_may_be_compared; m++)
            used |= uses_table(o->methods[m], names, defaults, candidates[k]);
        if (!used)
            t = candidates[k];
    }
    if (!t)
        return bf_fail(err, BF_EINPUT, "every candidate reference table is "
                       "compared; give --ref-table");
    if (bf_arkode_table_index(t) < 0)
        return bf_fail(err, BF_EINPUT, "unknown ARKODE table '%s'", t);
    for (size_t m = 0; m < o->n && !o->ref_may_be_compared; m++)
        if (uses_table(o->methods[m], names, defaults, t))
            return bf_fail(err, BF_EINPUT, "the reference table %s is also "
                           "compared (method '%s'); the reference must use "
                           "another method", t, o->methods[m]);
    *table = t;
    return BF_OK;
}

bf_status bf_study_arkode_reference(const bf_study_methods *o,
                                    const char *const *names,
                                    const char *const *defaults,
                                    const char *extra, char *method,
                                    size_t cap, bf_err *err)
{
    static const char *const refs[] = {"ARKODE_VERNER_8_5_6",
                                       "ARKODE_DORMAND_PRINCE_7_4_5",
                                       "ARKODE_CASH_KARP_6_4_5"};
    const char *table;
    bf_status st = bf_study_pick_table(o, names, defaults, refs, 3, &table,
                                       err);
    if (!st)
        snprintf(method, cap, "arkode:table=%s:max_steps=2000000000%s",
                 table, extra);
    return st;
}

bf_status bf_study_arkode_erk(const bf_model_setup *s,
                              const bf_study_methods *o, char *method,
                              size_t cap, bf_err *err)
{
    (void)s;
    static const char *const names[] = {"arkode", NULL};
    static const char *const defaults[] = {"ARKODE_DORMAND_PRINCE_7_4_5"};
    return bf_study_arkode_reference(o, names, defaults, "", method, cap,
                                     err);
}
