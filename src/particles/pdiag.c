/* pdiag.c: particle diagnostics (see pdiag.h). */
#include "pdiag.h"

#include <math.h>
#include <string.h>

bf_pdiag_acc bf_pdiag_acc_start(void)
{
    return (bf_pdiag_acc){{0, 0.0, NAN, INFINITY, -INFINITY}, 0.0};
}

void bf_pdiag_acc_add(bf_pdiag_acc *a, const bf_particles *p, int tag)
{
    bf_pdiag_group *g = &a->g;
    for (size_t i = 0; i < p->n; i++) {
        if (p->tag[i] != tag)
            continue;
        g->count++;
        a->sy += p->y[i];
        if (p->y[i] < g->min_y)
            g->min_y = p->y[i];
        if (p->y[i] > g->max_y)
            g->max_y = p->y[i];
        if (!(p->flags[i] & BF_PART_FIXED))
            g->kin += 0.5 * p->m[i] * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]);
    }
}

bf_pdiag_group bf_pdiag_acc_end(const bf_pdiag_acc *a)
{
    bf_pdiag_group g = a->g;
    if (g.count)
        g.mean_y = a->sy / (double)g.count;
    return g;
}

bf_pdiag_group bf_pdiag_group_of(const bf_particles *p, int tag)
{
    bf_pdiag_acc a = bf_pdiag_acc_start();
    bf_pdiag_acc_add(&a, p, tag);
    return bf_pdiag_acc_end(&a);
}

void bf_pdiag_layers(const bf_particles *p, int tag, double y0, double y1,
                     size_t nl, double *counts)
{
    memset(counts, 0, nl * sizeof *counts);
    bf_pdiag_layers_add(p, tag, y0, y1, nl, counts);
}

void bf_pdiag_layers_add(const bf_particles *p, int tag, double y0,
                         double y1, size_t nl, double *counts)
{
    const double scale = (double)nl / (y1 - y0);
    for (size_t i = 0; i < p->n; i++) {
        if (tag >= 0 && p->tag[i] != tag)
            continue;
        double f = floor((p->y[i] - y0) * scale);
        if (!(f >= 0))
            f = 0;
        size_t k = f >= (double)(nl - 1) ? nl - 1 : (size_t)f;
        counts[k] += 1.0;
    }
}

double bf_pdiag_cm_kinetic(const bf_particles *p, const double *inertia)
{
    double px = 0, py = 0, m = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->flags[i] & BF_PART_FIXED)
            continue;
        double mi = inertia ? inertia[i] : p->m[i];
        px += mi * p->vx[i];
        py += mi * p->vy[i];
        m += mi;
    }
    return m > 0 ? 0.5 * (px * px + py * py) / m : 0.0;
}

double bf_pdiag_kinetic(const bf_particles *p, const double *inertia)
{
    if (!inertia)
        return bf_particles_kinetic(p);
    double k = 0.0;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & BF_PART_FIXED))
            k += 0.5 * inertia[i] * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]);
    return k;
}
