/* arkode.h: helpers of the ARKODE adapter (src/integrators/arkode.c) for
 * the convergence driver, the first-order ARKODE driver (ark1.c) and the
 * tests: the Butcher tables it offers, whether the ARKODE 6.4.1 issue-311
 * work-around applies to a table, and the table with it applied. */
#ifndef BALLFILM_INTEGRATORS_ARKODE_H
#define BALLFILM_INTEGRATORS_ARKODE_H

#include <stddef.h>

#include <arkode/arkode_butcher.h>

/* The tables offered, in their order (the choices of a table key). */
#define BF_ARKODE_TABLE_CHOICES                                               \
    "ARKODE_HEUN_EULER_2_1_2|ARKODE_BOGACKI_SHAMPINE_4_2_3|"                  \
    "ARKODE_ARK324L2SA_ERK_4_2_3|ARKODE_ZONNEVELD_5_3_4|"                     \
    "ARKODE_ARK436L2SA_ERK_6_3_4|ARKODE_SAYFY_ABURUB_6_3_4|"                  \
    "ARKODE_CASH_KARP_6_4_5|ARKODE_FEHLBERG_6_4_5|"                           \
    "ARKODE_DORMAND_PRINCE_7_4_5|ARKODE_ARK548L2SA_ERK_8_4_5|"                \
    "ARKODE_VERNER_8_5_6|ARKODE_FEHLBERG_13_7_8|ARKODE_KNOTH_WOLKE_3_3|"      \
    "ARKODE_ARK437L2SA_ERK_7_3_4|ARKODE_ARK548L2SAb_ERK_8_4_5"

/* Number of tables offered by [integrator] table, their ARKODE names
 * ("ARKODE_DORMAND_PRINCE_7_4_5") and the index of a name (-1: unknown). */
size_t bf_arkode_ntables(void);
const char *bf_arkode_table_name(int index);
int bf_arkode_table_index(const char *name);

/* 1 if the table with this ARKODE_ERKTableID has last node c = 1 without
 * being first-same-as-last, so that this SUNDIALS version reuses a wrong
 * stage (issue 311) and the adapter pads it with an unused stage. */
int bf_arkode_table_needs_padding(int arkode_table_id);

/* The table of index `index` (bf_arkode_table_name), padded against issue
 * 311 when it needs it and work_around is set (*padded: whether it was);
 * NULL if it cannot be loaded.  Free it with ARKodeButcherTable_Free. */
ARKodeButcherTable bf_arkode_erk_table(int index, int work_around,
                                       int *padded);

#endif
