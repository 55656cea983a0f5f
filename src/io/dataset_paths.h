/* dataset_paths.h: the paths of the datasets that more than one file of
 * the library names (private to the library).  Each is written once
 * here: the model or loop that writes a dataset declares it in its
 * series table (series.h) with this name, and the readers that find it
 * again (sidecars, exports, sweeps) use the same name, so that a path
 * cannot drift between its writer and its readers. */
#ifndef BALLFILM_IO_DATASET_PATHS_H
#define BALLFILM_IO_DATASET_PATHS_H

#define BF_DS_BALLS_MASS                 "/balls/mass"
#define BF_DS_BALLS_POSITION             "/balls/position"
#define BF_DS_BALLS_RADIUS               "/balls/radius"
#define BF_DS_BALLS_VELOCITY             "/balls/velocity"
#define BF_DS_COUPLED_RETURN_MAP         "/coupled/return_map"
#define BF_DS_DIAG_KINETIC               "/diag/kinetic"
#define BF_DS_ENERGY_KINETIC             "/energy/kinetic"
#define BF_DS_ENERGY_POTENTIAL           "/energy/potential"
#define BF_DS_ENERGY_TOTAL               "/energy/total"
#define BF_DS_FILM_H                     "/film/h"
#define BF_DS_FILM_PSI                   "/film/psi"
#define BF_DS_FILM_TIME                  "/film/time"
#define BF_DS_FILM_U_C                   "/film/u_c"
#define BF_DS_FILM_U_D                   "/film/u_d"
#define BF_DS_FILM_X                     "/film/x"
#define BF_DS_MAC_T                      "/mac/T"
#define BF_DS_MAC_FLAGS                  "/mac/flags"
#define BF_DS_MAC_GRID                   "/mac/grid"
#define BF_DS_MAC_P                      "/mac/p"
#define BF_DS_MAC_PARTICLES_DENSITY      "/mac/particles/density"
#define BF_DS_MAC_PARTICLES_FLAG         "/mac/particles/flag"
#define BF_DS_MAC_PARTICLES_X            "/mac/particles/x"
#define BF_DS_MAC_PARTICLES_Y            "/mac/particles/y"
#define BF_DS_MAC_RHO                    "/mac/rho"
#define BF_DS_MAC_U                      "/mac/u"
#define BF_DS_MAC_V                      "/mac/v"
#define BF_DS_PARTICLES_FIXED            "/particles/fixed"
#define BF_DS_PARTICLES_GRAVITY          "/particles/gravity"
#define BF_DS_PARTICLES_INERTIA          "/particles/inertia"
#define BF_DS_PARTICLES_MASS             "/particles/mass"
#define BF_DS_PARTICLES_STEP             "/particles/step"
#define BF_DS_PARTICLES_TAG              "/particles/tag"
#define BF_DS_PARTICLES_VX               "/particles/vx"
#define BF_DS_PARTICLES_VY               "/particles/vy"
#define BF_DS_PARTICLES_X                "/particles/x"
#define BF_DS_PARTICLES_Y                "/particles/y"
#define BF_DS_RETURN_MAP_V               "/return_map/v"
#define BF_DS_RETURN_MAP_Z               "/return_map/z"
#define BF_DS_STEP                       "/step"
#define BF_DS_TIME                       "/time"

#endif
