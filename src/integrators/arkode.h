/* arkode.h: helpers of the ARKODE adapter (src/integrators/arkode.c) for
 * the convergence driver and the tests: the Butcher tables it offers and
 * whether the ARKODE 6.4.1 issue-311 work-around applies to a table. */
#ifndef BALLFILM_INTEGRATORS_ARKODE_H
#define BALLFILM_INTEGRATORS_ARKODE_H

#include <stddef.h>

/* Number of tables offered by [integrator] table, their ARKODE names
 * ("ARKODE_DORMAND_PRINCE_7_4_5") and the index of a name (-1: unknown). */
size_t bf_arkode_ntables(void);
const char *bf_arkode_table_name(int index);
int bf_arkode_table_index(const char *name);

/* 1 if the table with this ARKODE_ERKTableID has last node c = 1 without
 * being first-same-as-last, so that this SUNDIALS version reuses a wrong
 * stage (issue 311) and the adapter pads it with an unused stage. */
int bf_arkode_table_needs_padding(int arkode_table_id);

#endif
