/* version.h: program version (the build adds the git commit). */
#ifndef BALLFILM_VERSION_H
#define BALLFILM_VERSION_H

#define BF_VERSION "0.1.0"

/* "ballfilm 0.1.0 (git <commit>)" */
const char *bf_version_string(void);

#endif
