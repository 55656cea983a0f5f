/* version.h: program version (the build adds the git commit). */
#ifndef BALLFILM_VERSION_H
#define BALLFILM_VERSION_H

#define BF_VERSION "0.2.0"

/* "ballfilm 0.2.0 (git <commit>)" */
const char *bf_version_string(void);

#endif
