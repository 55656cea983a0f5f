/* ipow.h: b^e for integer e >= 0 (the force laws of Greenspan's models use
 * integer exponents).  The small exponents are written out (a switch on a
 * value that does not change within a run is predicted), the others by
 * repeated squaring. */
#ifndef BALLFILM_PARTICLES_IPOW_H
#define BALLFILM_PARTICLES_IPOW_H

static inline double bf_ipow(double b, int e)
{
    switch (e) {
    case 0:
        return 1.0;
    case 1:
        return b;
    case 2:
        return b * b;
    case 3:
        return b * b * b;
    case 4: {
        double b2 = b * b;
        return b2 * b2;
    }
    case 5: {
        double b2 = b * b;
        return b2 * b2 * b;
    }
    default: {
        double r = 1.0;
        while (e) {
            if (e & 1)
                r *= b;
            b *= b;
            e >>= 1;
        }
        return r;
    }
    }
}

#endif
