/* mac_grid.c: the grid helpers of the MAC solver (see mac_grid.h): the
 * flood over interior cells and the faces of a cell. */
#include "mac/mac_grid.h"

void bf_mac_flood(bf_mac *m, int n, int (*pass)(int flag))
{
    const int nyu = m->nj - 2;
    const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
    for (int head = 0; head < n;) {
        int k = m->queue[head++];
        int i = k / nyu + 2, j = k % nyu + 2;
        for (int d = 0; d < 4; d++) {
            int a = i + di[d], b = j + dj[d];
            if (!mac_interior(m, a, b) || !pass(m->ic[IX(a, b)]))
                continue;
            int kk = mac_unk(m, a, b);
            if (!m->mark[kk]) {
                m->mark[kk] = 1;
                m->queue[n++] = kk;
            }
        }
    }
}

void bf_mac_face_of(const bf_mac *m, int i, int j, int d, mac_face *f)
{
    const double *R = m->r;
    switch (d) {
    case MAC_E:
        f->i = i + 1, f->j = j, f->delta = m->dx, f->s = 1;
        f->psi = m->xi[IX(i + 1, j)];
        f->rhof = 0.5 * (R[IX(i, j)] + R[IX(i + 1, j)]);
        break;
    case MAC_W:
        f->i = i - 1, f->j = j, f->delta = m->dx, f->s = -1;
        f->psi = m->xi[IX(i, j)];
        f->rhof = 0.5 * (R[IX(i - 1, j)] + R[IX(i, j)]);
        break;
    case MAC_N:
        f->i = i, f->j = j + 1, f->delta = m->dy, f->s = 1;
        f->psi = m->zeta[IX(i, j + 1)];
        f->rhof = 0.5 * (R[IX(i, j)] + R[IX(i, j + 1)]);
        break;
    default:
        f->i = i, f->j = j - 1, f->delta = m->dy, f->s = -1;
        f->psi = m->zeta[IX(i, j)];
        f->rhof = 0.5 * (R[IX(i, j - 1)] + R[IX(i, j)]);
        break;
    }
}
