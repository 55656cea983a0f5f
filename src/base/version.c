/* version.c: the version string stored in every output file. */
#include "ballfilm/version.h"

#ifndef BF_GIT
#define BF_GIT "unknown"
#endif

const char *bf_version_string(void)
{
    return "ballfilm " BF_VERSION " (git " BF_GIT ")";
}
