/* script.c: scenes written in code (run.h): keys set like printf, balls
 * added one by one.  Both are overrides of the scene (bf_scene_set), so a
 * scene made in code is validated, recorded and restarted like a file's. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "ballfilm/run.h"

/* The longest assignment (a list of particle positions may be long). */
enum { MAX_SET = 1 << 16 };

bf_status bf_setf(bf_scene *sc, bf_err *err, const char *fmt, ...)
{
    static const char origin[] = "code";
    if (!sc || !fmt)
        return bf_fail(err, BF_EINPUT, "bf_setf: %s is NULL",
                       !sc ? "the scene" : "fmt");
    char *buf = malloc(MAX_SET);
    if (!buf)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    va_list ap;
    va_start(ap, fmt);
    int w = vsnprintf(buf, MAX_SET, fmt, ap);
    va_end(ap);
    bf_status st = w < 0 || w >= MAX_SET
                       ? bf_fail(err, BF_EINPUT, "%s: error: an assignment "
                                 "longer than %d characters", origin, MAX_SET)
                       : bf_scene_set(sc, buf, origin, err);
    free(buf);
    return st;
}

bf_status bf_add_ball(bf_scene *sc, double position, double velocity,
                      double mass, double radius, int *index, bf_err *err)
{
    const double v[4] = {position, velocity, mass, radius};
    static const char *const what[4] = {"position", "velocity", "mass",
                                        "radius"};
    if (!sc)
        return bf_fail(err, BF_EINPUT, "bf_add_ball: the scene is NULL");
    /* %.17g of a NaN is "nan", which would be refused later naming a key
     * of a scene the caller never wrote */
    for (int k = 0; k < 4; k++)
        if (!isfinite(v[k]))
            return bf_fail(err, BF_EINPUT, "bf_add_ball: %s = %g is not "
                           "finite", what[k], v[k]);
    char name[32];
    int n = 1;
    for (;; n++) {
        snprintf(name, sizeof name, "ball.%d", n);
        if (!bf_scene_has_section(sc, name))
            break;
    }
    bf_status st = bf_setf(sc, err, "%s.position=%.17g", name, position);
    if (!st)
        st = bf_setf(sc, err, "%s.velocity=%.17g", name, velocity);
    if (!st)
        st = bf_setf(sc, err, "%s.mass=%.17g", name, mass);
    if (!st)
        st = bf_setf(sc, err, "%s.radius=%.17g", name, radius);
    if (!st && index)
        *index = n;
    return st;
}
