/* film_state.c: the arrays that make up the film's state and its
 * checkpoint (film.h), as a table of fields (checkpoint.h).  The entries
 * are PREFIX.ah_d, .ah_c, .u_d, .u_c, .ah_d_rounding, .ah_c_rounding (the
 * nodes 0..N) and PREFIX.limiter (the limiter's step and face counts). */
#include "ballfilm/film.h"

#include "film/film_impl.h"

/* the state arrays in the order of bf_film_state */
static const int state_vars[BF_FILM_NSTATE] = {V_AD, V_AC, V_UD,
                                               V_UC, V_KD, V_KC};

size_t bf_film_state(bf_film *f, double *arr[BF_FILM_NSTATE])
{
    for (int k = 0; k < BF_FILM_NSTATE; k++)
        arr[k] = ARR(f, state_vars[k]);
    return (size_t)f->N + 1;
}

/* What a checkpoint holds: the film's arrays (pointers into it) and its
 * counters. */
typedef struct film_ckpt {
    size_t n; /* nodes */
    double *ah_d, *ah_c, *u_d, *u_c, *ah_d_rounding, *ah_c_rounding;
    unsigned long long limiter[2]; /* steps, faces */
} film_ckpt;

static const bf_field film_fields[] = {
    BF_FIELD_PTR(film_ckpt, ah_d, BF_F_DOUBLE, n, "cm"),
    BF_FIELD_PTR(film_ckpt, ah_c, BF_F_DOUBLE, n, "cm"),
    BF_FIELD_PTR(film_ckpt, u_d, BF_F_DOUBLE, n, "cm/s"),
    BF_FIELD_PTR(film_ckpt, u_c, BF_F_DOUBLE, n, "cm/s"),
    BF_FIELD_PTR(film_ckpt, ah_d_rounding, BF_F_DOUBLE, n, "cm"),
    BF_FIELD_PTR(film_ckpt, ah_c_rounding, BF_F_DOUBLE, n, "cm"),
    BF_FIELD_ARRAY(film_ckpt, limiter, BF_F_ULL, "1"),
};

static film_ckpt ckpt_of(const bf_film *f)
{
    film_ckpt c = {
        .n = (size_t)f->N + 1,
        .ah_d = ARR(f, V_AD),
        .ah_c = ARR(f, V_AC),
        .u_d = ARR(f, V_UD),
        .u_c = ARR(f, V_UC),
        .ah_d_rounding = ARR(f, V_KD),
        .ah_c_rounding = ARR(f, V_KC),
        .limiter = {f->lim_steps, f->lim_faces},
    };
    return c;
}

bf_status bf_film_save(const bf_film *f, bf_ckpt *ck, const char *prefix,
                       bf_err *err)
{
    film_ckpt c = ckpt_of(f);
    return bf_ckpt_put_fields(ck, prefix, film_fields, BF_NFIELDS(film_fields),
                              &c, err);
}

bf_status bf_film_load(bf_film *f, const bf_ckpt *ck, const char *prefix,
                       bf_err *err)
{
    film_ckpt c = ckpt_of(f);
    bf_status st = bf_ckpt_get_fields(ck, prefix, film_fields,
                                      BF_NFIELDS(film_fields), &c, err);
    if (st)
        return st;
    f->lim_steps = c.limiter[0];
    f->lim_faces = c.limiter[1];
    bf_film_state_changed(f);
    return BF_OK;
}
