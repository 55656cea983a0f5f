# bench/driver/build.sh: how the scripts in bench/ build a driver of
# bench/driver against a libballfilm.a (sourced, not run; from the
# repository's top directory): the library's own compiler flags (the
# Makefile's CSTD) and the libraries that libballfilm.a needs at link time.
# shellcheck shell=bash
DRIVER_CFLAGS="-std=c11 -O2 -Wall -Wextra -Werror -ffp-contract=off -D_POSIX_C_SOURCE=200809L"
DRIVER_INC="$(pkg-config --cflags hdf5-serial gsl)"
DRIVER_LIBS="$(pkg-config --libs hdf5-serial) -lhdf5_hl -lsundials_arkode \
  -lsundials_nvecserial -linih $(pkg-config --libs gsl) -lm -fopenmp"

# driver_library DIR: this tree's build/libballfilm.a brought up to date,
# the log in DIR/build.log (its end printed, and the script stopped, if
# the build fails).
driver_library() {
    make --no-print-directory -j2 build/libballfilm.a > "$1/build.log" 2>&1 ||
        { tail -20 "$1/build.log"; exit 1; }
}
