# bench/driver/build.sh: how the scripts in bench/ build a driver of
# bench/driver against a libballfilm.a (sourced, not run; from the
# repository's top directory): the library's own compiler flags (the
# Makefile's CSTD) and the libraries that libballfilm.a needs at link time.
# shellcheck shell=bash
DRIVER_CFLAGS="-std=c11 -O2 -Wall -Wextra -Werror -ffp-contract=off -D_POSIX_C_SOURCE=200809L"
DRIVER_INC="$(pkg-config --cflags hdf5-serial gsl)"
DRIVER_LIBS="$(pkg-config --libs hdf5-serial) -lhdf5_hl -lsundials_arkode \
  -lsundials_nvecserial -linih $(pkg-config --libs gsl) -lm -fopenmp"

# driver_library LOG [TREE]: TREE's build/libballfilm.a (default this
# tree's) brought up to date, the log in LOG (its end printed, and the
# script stopped, if the build fails).
driver_library() {
    make --no-print-directory -C "${2:-.}" -j2 build/libballfilm.a > "$1" 2>&1 ||
        { tail -20 "$1"; exit 1; }
}
