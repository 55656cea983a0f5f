# ballfilm: balls and particle fluids in thin liquid films.
#
#   make run       install missing packages, build, run the default scene,
#                  draw its figure (out/)
#   make test      build and run the test suite
#   make check     the test suite under AddressSanitizer + UBSan
#   make figures   every paper figure (long runs; docs/gallery.md lists them)
#   make bench     performance measurements (ratios measured in one run)
#   make fuzz      the fuzzers (scenes, checkpoints, then fuzz-h5: the
#                  readers of output files; FUZZ_H5_SECONDS, FUZZ_H5_SEED)
#   make clean
#
# Debian 12 packages are installed automatically when run as root; otherwise
# the exact apt-get line is printed.

SHELL := /bin/bash
.DEFAULT_GOAL := all

BUILD_PKGS := gcc make pkg-config libsundials-dev libgsl-dev libhdf5-dev \
              hdf5-tools libinih-dev check openmpi-bin libopenmpi-dev
PLOT_PKGS  := python3-numpy python3-matplotlib python3-h5py
MOVIE_PKGS := ffmpeg python3-pil
XDMF_PKGS  := paraview
UNITS_PKGS := udunits-bin
EXPORT_PKGS := python3-mdanalysis python3-ase
PY         := /usr/bin/python3

# ---------------------------------------------------------------- flags
BUILD   ?= build
BINDIR  ?= bin
SANITIZE ?=
GIT     := $(shell git rev-parse --short HEAD 2>/dev/null || echo unknown)
# The commit named in the version string (src/base/version.c, written into
# every output file) is a compiler flag, which make does not track: a file
# holding it, rewritten only when HEAD has moved, makes version.o older
# than it then, so that an incremental build names the right commit.
GIT_STAMP := $(BUILD)/git-commit
$(shell mkdir -p $(BUILD) && { [ "$$(cat $(GIT_STAMP) 2>/dev/null)" = "$(GIT)" ] || \
  echo "$(GIT)" > $(GIT_STAMP); })

CC       = gcc
CSTD     = -std=c11 -O2 -Wall -Wextra -Werror -ffp-contract=off
CPPFLAGS = -Iinclude -Isrc -D_POSIX_C_SOURCE=200809L -DBF_GIT='"$(GIT)"' \
           $(shell pkg-config --cflags hdf5-serial gsl 2>/dev/null)
CFLAGS   = $(CSTD) $(SANITIZE) -MMD -MP
LDLIBS   = $(shell pkg-config --libs hdf5-serial 2>/dev/null) -lhdf5_hl \
           -lsundials_arkode -lsundials_nvecserial -linih \
           $(shell pkg-config --libs gsl 2>/dev/null) -lm -fopenmp
LDFLAGS  = $(SANITIZE)
# The program links the libraries it uses statically when their archives
# are installed (Debian's -dev packages ship them): Debian's shared HDF5
# pulls in curl, TLS and Kerberos (42 shared objects in all), whose
# loading was most of the start-up of a small run; the archives bring only
# the objects ballfilm calls.  Same code, same results; `make bench`
# (bench/startup.sh) prints the start-up time and memory.
ARCHIVE_DIRS := /usr/lib/x86_64-linux-gnu/hdf5/serial /usr/lib/x86_64-linux-gnu \
                /usr/lib/$(shell gcc -print-multiarch 2>/dev/null)
STATIC_LIBS  := hdf5_hl hdf5 sundials_arkode sundials_nvecserial inih gsl \
                gslcblas sz aec z
STATIC_FOUND := $(foreach l,$(STATIC_LIBS),$(firstword $(wildcard \
                  $(foreach d,$(ARCHIVE_DIRS),$(d)/lib$(l).a))))
# The program is linked at a fixed address (-no-pie): its 3200 relative
# relocations (every pointer in a table of functions or names) are then
# resolved by the linker instead of at every start, which wrote to some 20
# pages of the binary before main (bench/startup.sh: about 0.3 ms of the
# 10 ms of a small run on the AMD machine of docs/performance.md).  The
# price: the program's own code is not at a random address (its libraries,
# heap and stack still are); it reads files and writes files, it serves
# no one.  The library (libballfilm.a, .so) is unchanged.
# OpenMP's runtime too, from gcc's own archive where it has one (loading
# libgomp.so was about 0.3 ms of that start-up); not with clang, whose
# OpenMP code calls its own runtime (libomp), not libgomp.
CC_IS_CLANG  := $(shell $(CC) -dM -E - </dev/null 2>/dev/null | grep -c __clang__)
GOMP_ARCHIVE := $(if $(filter 0,$(CC_IS_CLANG)),$(wildcard $(shell \
                  $(CC) -print-file-name=libgomp.a 2>/dev/null)))
PROG_OMP     := $(if $(GOMP_ARCHIVE),$(GOMP_ARCHIVE) -lpthread,-fopenmp)
ifeq ($(words $(STATIC_FOUND)),$(words $(STATIC_LIBS)))
PROG_LDLIBS = $(STATIC_FOUND) -lm $(PROG_OMP) -ldl -no-pie
else
PROG_LDLIBS = $(LDLIBS)
endif
CHECK_CFLAGS = $(shell pkg-config --cflags check 2>/dev/null)
CHECK_LIBS   = $(shell pkg-config --libs check 2>/dev/null)

# ---------------------------------------------------------------- sources
LIB_SRC  := $(sort $(filter-out src/cli/%,$(wildcard src/*/*.c)))
CLI_SRC  := $(sort $(wildcard src/cli/*.c))
TEST_SRC := $(sort $(wildcard tests/test_*.c))
# tests/killwrite.c is a preloaded library of its own (KILLWRITE below),
# not a part of the runner, whose own writes it would otherwise wrap.
TEST_AUX := $(sort $(filter-out tests/test_% tests/killwrite.c,$(wildcard tests/*.c)))
BENCH_SRC := $(sort $(wildcard bench/*.c))

LIB_OBJ   := $(LIB_SRC:%.c=$(BUILD)/obj/%.o)
CLI_OBJ   := $(CLI_SRC:%.c=$(BUILD)/obj/%.o)
TEST_OBJ  := $(TEST_SRC:%.c=$(BUILD)/obj/%.o) $(TEST_AUX:%.c=$(BUILD)/obj/%.o)
BENCH_BIN := $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%)
LIB       := $(BUILD)/libballfilm.a
PROG      := $(BINDIR)/ballfilm
RUNNER    := $(BUILD)/tests/runner

.PHONY: all run test check figures bench clean deps deps-plot test-run test-static \
        build-tests fig1 fuzz fuzz-h5 valgrind mpi stratres mac-checks fig2 fig3 fig8-offset \
        fig4 converge-figures survey-mass survey-length fig-vibrating-table fig5 kink-dx2 \
        film-orders fig6 fig8 fig9 fig8-sym fig9-sym sym-divergence \
        fig9-scan fig9-confirm fig9-islands \
        multirate fig-g72-ex1 \
        fig-g72-ex1-ensemble fig-g72-ex2 fig-g72-large fig-g73-hex \
        fig-g73-wall movies deps-movies deps-xdmf test-movies test-xdmf deps-units test-units \
        deps-export test-export \
        shared install uninstall man deps-install test-install test-examples \
        test-python deps-python test-pip deps-pip test-notebooks \
        deps-notebooks test-cli-docs deps-cli-docs

all: $(PROG) shared

$(BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@

$(BUILD)/obj/tests/%.o: tests/%.c $(BUILD)/tests/suites.inc
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) -I$(BUILD)/tests $(CHECK_CFLAGS) $(CFLAGS) -c $< -o $@

# OpenMP (libgomp, part of gcc) only where it pays: the particle forces.
# Their results do not depend on the number of threads (tested).
OMP_OBJ := $(addprefix $(BUILD)/obj/,src/particles/support_setup.o \
             src/particles/support_cell.o src/particles/support_fast.o \
             src/particles/repulsion.o src/models/greenspan72.o)
$(OMP_OBJ): CFLAGS += -fopenmp

$(LIB): $(LIB_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	ar rcs $@ $^

$(PROG): $(CLI_OBJ) $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) -o $@ $(CLI_OBJ) $(LIB) $(PROG_LDLIBS)

# ---------------------------------------------------------------- shared library
# libballfilm.so from a second set of objects compiled with -fPIC
# (build/pic/).  The soname carries the ABI: the major version, and while
# the major version is 0 also the minor one (every 0.x may change the
# ABI): libballfilm.so.0.2 for 0.2.0.  Only the functions and variables
# that the public headers declare are exported (a version script made from
# the headers, comments stripped, and the objects' symbols); everything
# else, bf_-prefixed internals included, is local.  The program and the
# tests link the static library.
VERSION    := $(shell sed -n 's/^\#define BF_VERSION "\(.*\)"/\1/p' include/ballfilm/version.h)
VMAJOR     := $(word 1,$(subst ., ,$(VERSION)))
VMINOR     := $(word 2,$(subst ., ,$(VERSION)))
ABI        := $(if $(filter 0,$(VMAJOR)),$(VMAJOR).$(VMINOR),$(VMAJOR))
SONAME     := libballfilm.so.$(ABI)
SHLIB      := $(BUILD)/libballfilm.so.$(VERSION)
PUBLIC_H   := $(sort $(wildcard include/ballfilm/*.h))
PIC_OBJ    := $(LIB_SRC:%.c=$(BUILD)/pic/obj/%.o)
$(BUILD)/obj/src/base/version.o $(BUILD)/pic/obj/src/base/version.o: $(GIT_STAMP)
PIC_OMP    := $(OMP_OBJ:$(BUILD)/obj/%=$(BUILD)/pic/obj/%)
SHLIB_LIBS := $(shell pkg-config --libs hdf5-serial 2>/dev/null) \
              -lsundials_arkode -lsundials_nvecserial -linih \
              $(shell pkg-config --libs gsl 2>/dev/null) -lm -lgomp -lpthread

$(BUILD)/pic/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -fPIC -fno-semantic-interposition -c $< -o $@
$(PIC_OMP): CFLAGS += -fopenmp

$(BUILD)/libballfilm.map: $(PIC_OBJ) $(PUBLIC_H)
	@for h in $(PUBLIC_H); do $(CC) -fpreprocessed -dD -E -P $$h; done \
	  | grep -oE '\bbf_[A-Za-z0-9_]+' | sort -u > $@.api
	@nm -g --defined-only $(PIC_OBJ) | awk 'NF == 3 { print $$3 }' \
	  | sort -u > $@.defined
	@{ echo '{ global:'; comm -12 $@.api $@.defined | sed 's/.*/  &;/'; \
	   echo '  local: *; };'; } > $@.tmp
	@rm -f $@.api $@.defined
	@mv $@.tmp $@

$(SHLIB): $(PIC_OBJ) $(BUILD)/libballfilm.map
	$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--version-script=$(BUILD)/libballfilm.map \
	  -Wl,--no-undefined -Wl,--as-needed $(LDFLAGS) -o $@ $(PIC_OBJ) $(SHLIB_LIBS)
	ln -sf $(notdir $@) $(BUILD)/$(SONAME)
	ln -sf $(SONAME) $(BUILD)/libballfilm.so

shared: $(SHLIB)

# ---------------------------------------------------------------- install
# make install [PREFIX=/usr/local] [DESTDIR=...]: the program, both
# libraries, the public headers, ballfilm.pc (pkg-config), the man page
# (src/cli/ballfilm.1.in with the scene keys of the program's own table,
# src/cli/mkman.py), the bash completion, the Python package, and in
# PREFIX/share/ballfilm the scenes (runs/) and the plot scripts (plots/)
# that `ballfilm animate` and the figures run (the program finds them
# beside itself: PREFIX/bin/../share/ballfilm), and the documentation in
# PREFIX/share/doc/ballfilm.
# make uninstall removes exactly those files (same PREFIX and DESTDIR).
PREFIX     ?= /usr/local
LIBDIR     ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
MANDIR     ?= $(PREFIX)/share/man
PYVER      := $(shell $(PY) -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null)
PYTHONDIR  ?= $(PREFIX)/lib/python$(PYVER)/dist-packages
PY_PKG     := $(sort $(wildcard python/ballfilm/*.py))
SHAREDIR   ?= $(PREFIX)/share/ballfilm
DOCDIR     ?= $(PREFIX)/share/doc/ballfilm
SHARE_RUNS := $(sort $(wildcard runs/*.ini runs/*.sh))
SHARE_PLOTS := $(sort $(wildcard plots/*.py))
DOC_TOP    := README.md
DOC_PAGES  := $(sort $(wildcard docs/*.md))
DOC_MODELS := $(sort $(wildcard docs/models/*.md))
MAN        := $(BUILD)/ballfilm.1
BASHCOMPDIR ?= $(PREFIX)/share/bash-completion/completions
INSTALL_PKGS := pkg-config

deps-install:
	$(call need_pkgs,$(INSTALL_PKGS))

$(MAN): $(PROG) src/cli/ballfilm.1.in src/cli/mkman.py
	$(PY) src/cli/mkman.py $(PROG) src/cli/ballfilm.1.in $(VERSION) > $@.tmp
	mv $@.tmp $@
man: $(MAN)

# The installed package finds the installed library through _install.py.
install: $(PROG) $(LIB) $(SHLIB) $(MAN)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(LIBDIR)/pkgconfig \
	  $(DESTDIR)$(INCLUDEDIR)/ballfilm $(DESTDIR)$(MANDIR)/man1 \
	  $(DESTDIR)$(PYTHONDIR)/ballfilm $(DESTDIR)$(SHAREDIR)/runs \
	  $(DESTDIR)$(SHAREDIR)/plots $(DESTDIR)$(DOCDIR)/docs/models
	install -m 755 $(PROG) $(DESTDIR)$(PREFIX)/bin/ballfilm
	install -m 644 $(LIB) $(DESTDIR)$(LIBDIR)/libballfilm.a
	install -m 755 $(SHLIB) $(DESTDIR)$(LIBDIR)/$(notdir $(SHLIB))
	ln -sf $(notdir $(SHLIB)) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libballfilm.so
	install -m 644 $(PUBLIC_H) $(DESTDIR)$(INCLUDEDIR)/ballfilm/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' \
	    -e 's|@INCLUDEDIR@|$(INCLUDEDIR)|' -e 's|@VERSION@|$(VERSION)|' \
	    src/ballfilm.pc.in > $(DESTDIR)$(LIBDIR)/pkgconfig/ballfilm.pc
	install -m 644 $(MAN) $(DESTDIR)$(MANDIR)/man1/ballfilm.1
	install -D -m 644 src/cli/ballfilm.bash $(DESTDIR)$(BASHCOMPDIR)/ballfilm
	$(if $(PY_PKG),install -m 644 $(PY_PKG) $(DESTDIR)$(PYTHONDIR)/ballfilm/)
	printf 'LIBRARY = "%s"\nSHARE = "%s"\n' $(LIBDIR)/$(SONAME) $(SHAREDIR) \
	  > $(DESTDIR)$(PYTHONDIR)/ballfilm/_install.py
	printf 'version = "%s"\n' $(VERSION) > $(DESTDIR)$(PYTHONDIR)/ballfilm/_version.py
	install -m 644 $(SHARE_RUNS) $(DESTDIR)$(SHAREDIR)/runs/
	install -m 644 $(SHARE_PLOTS) $(DESTDIR)$(SHAREDIR)/plots/
	install -m 644 $(DOC_TOP) $(DESTDIR)$(DOCDIR)/
	install -m 644 $(DOC_PAGES) $(DESTDIR)$(DOCDIR)/docs/
	install -m 644 $(DOC_MODELS) $(DESTDIR)$(DOCDIR)/docs/models/

uninstall:
	rm -f $(DESTDIR)$(PREFIX)/bin/ballfilm $(DESTDIR)$(LIBDIR)/libballfilm.a \
	  $(DESTDIR)$(LIBDIR)/libballfilm.so $(DESTDIR)$(LIBDIR)/$(SONAME) \
	  $(DESTDIR)$(LIBDIR)/$(notdir $(SHLIB)) \
	  $(DESTDIR)$(LIBDIR)/pkgconfig/ballfilm.pc \
	  $(DESTDIR)$(MANDIR)/man1/ballfilm.1 \
	  $(DESTDIR)$(BASHCOMPDIR)/ballfilm \
	  $(addprefix $(DESTDIR)$(INCLUDEDIR)/ballfilm/,$(notdir $(PUBLIC_H))) \
	  $(addprefix $(DESTDIR)$(PYTHONDIR)/ballfilm/,$(notdir $(PY_PKG)) _install.py _version.py) \
	  $(addprefix $(DESTDIR)$(SHAREDIR)/runs/,$(notdir $(SHARE_RUNS))) \
	  $(addprefix $(DESTDIR)$(SHAREDIR)/plots/,$(notdir $(SHARE_PLOTS))) \
	  $(addprefix $(DESTDIR)$(DOCDIR)/,$(DOC_TOP) $(DOC_PAGES) $(DOC_MODELS))
	rm -rf $(DESTDIR)$(PYTHONDIR)/ballfilm/__pycache__ \
	  $(DESTDIR)$(SHAREDIR)/plots/__pycache__
	-rmdir $(DESTDIR)$(INCLUDEDIR)/ballfilm $(DESTDIR)$(PYTHONDIR)/ballfilm \
	  $(DESTDIR)$(SHAREDIR)/runs $(DESTDIR)$(SHAREDIR)/plots $(DESTDIR)$(SHAREDIR) \
	  $(DESTDIR)$(DOCDIR)/docs/models $(DESTDIR)$(DOCDIR)/docs $(DESTDIR)$(DOCDIR) \
	  2>/dev/null

# The MPI front end: the same CLI compiled with mpicc and -DBF_MPI (only the
# sweep command uses MPI), linked with the same library.
MPI_PROG := $(BINDIR)/ballfilm-mpi
MPI_OBJ  := $(CLI_SRC:%.c=$(BUILD)/mpi/%.o)
mpi: $(MPI_PROG)
$(BUILD)/mpi/%.o: %.c
	@mkdir -p $(dir $@)
	mpicc $(CPPFLAGS) -DBF_MPI $(CFLAGS) -c $< -o $@
$(MPI_PROG): $(MPI_OBJ) $(LIB)
	@mkdir -p $(dir $@)
	mpicc $(LDFLAGS) -pthread -o $@ $(MPI_OBJ) $(LIB) $(LDLIBS)

# Every tests/test_NAME.c defines `Suite *suite_NAME(void)`; the runner
# collects them from this generated list, so adding a test file needs no
# other edit.
$(BUILD)/tests/suites.inc: $(TEST_SRC) Makefile
	@mkdir -p $(dir $@)
	@( $(foreach t,$(TEST_SRC),echo 'BF_SUITE($(patsubst tests/test_%.c,%,$(t)))';) ) > $@.tmp
	@mv $@.tmp $@

$(RUNNER): $(TEST_OBJ) $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) -o $@ $(TEST_OBJ) $(LIB) $(CHECK_LIBS) $(LDLIBS)

$(BUILD)/bench/%: bench/%.c $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -o $@ $< $(LIB) $(LDLIBS)

-include $(shell find $(BUILD)/obj $(BUILD)/pic -name '*.d' 2>/dev/null)

# ---------------------------------------------------------------- packages
# deps: what building and testing needs; deps-plot: what the figures need.
define need_pkgs
	@if ! command -v dpkg-query >/dev/null; then \
	  echo "note: not a Debian system; make sure these are installed: $(1)"; \
	else \
	  missing=""; \
	  for p in $(1); do \
	    dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' \
	      || missing="$$missing $$p"; \
	  done; \
	  if [ -n "$$missing" ]; then \
	    if [ "$$(id -u)" = 0 ]; then \
	      echo "installing:$$missing"; \
	      apt-get update -q && \
	      DEBIAN_FRONTEND=noninteractive apt-get install -y -q $$missing || exit 1; \
	    else \
	      echo "missing Debian packages; install them with:"; \
	      echo "  sudo apt-get install -y$$missing"; \
	      exit 1; \
	    fi; \
	  fi; \
	fi
endef

deps:
	$(call need_pkgs,$(BUILD_PKGS))

deps-plot:
	$(call need_pkgs,$(PLOT_PKGS))

deps-movies:
	$(call need_pkgs,$(PLOT_PKGS) $(MOVIE_PKGS))

deps-xdmf:
	$(call need_pkgs,$(PLOT_PKGS) $(XDMF_PKGS))

deps-units:
	$(call need_pkgs,$(PLOT_PKGS) $(UNITS_PKGS))

deps-export:
	$(call need_pkgs,$(PLOT_PKGS) $(EXPORT_PKGS))

# ---------------------------------------------------------------- main job
run:
	@$(MAKE) --no-print-directory deps deps-plot
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory fig1
	@echo
	@echo "results:  out/bouncing_ball_verlet.h5  out/bouncing_ball_mv2m.h5"
	@echo "figure:   out/fig1_phase.png"

# Yasuda Fig. 1: the bouncing ball, Verlet beside MV2M (dt = 3e-4 s, 100 s).
fig1: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/bouncing_ball.ini -q -o out/bouncing_ball_verlet.h5 \
	    --set scene.integrator=verlet
	$(PROG) run runs/bouncing_ball.ini -q -o out/bouncing_ball_mv2m.h5 \
	    --set scene.integrator=mv2m
	$(PY) plots/fig1_phase.py out/bouncing_ball_verlet.h5 \
	    out/bouncing_ball_mv2m.h5 -o out/fig1_phase.png


# Thesis (MAC) Fig. 5: the stratified reservoir with a point sink to t = 10,
# and the same at 2x and 4x the grid (4x traps empty cells inside the fluid;
# void_fix fills them, see docs/models/mac.md).
stratres: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/stratres.ini -q -o out/stratres.h5
	$(PY) plots/fig_stratres.py out/stratres.h5 -o out/stratres.png
	$(PROG) run runs/stratres.ini -q -o out/stratres_x2.h5 \
	    --set mac.refine=2 --set scene.dt=0.025 --set scene.output_every=20
	$(PY) plots/fig_stratres.py out/stratres_x2.h5 -o out/stratres_x2.png
	$(PROG) run runs/stratres.ini -q -o out/stratres_x4.h5 \
	    --set mac.refine=4 --set scene.dt=0.0125 --set scene.output_every=40 \
	    --set mac.void_fix=true
	$(PY) plots/fig_stratres.py out/stratres_x4.h5 -o out/stratres_x4.png

# The thesis's two checks (tank at rest, uniform stream) for every velocity
# update, with the exact pressure solve and with the listing's relaxation;
# the tank at rest both stratified and homogeneous (mac.rho_amp = 0).
MAC_VARIANTS := printed consistent original
mac-checks: $(PROG) | deps deps-plot
	@mkdir -p out
	@set -e; for u in $(MAC_VARIANTS); do for s in direct relax; do \
	  $(PROG) run runs/mac_rest.ini -q -o out/mac_rest_$${u}_$$s.h5 \
	    --set mac.update=$$u --set mac.pressure_solver=$$s \
	    --set scene.output_every=1 >/dev/null; \
	  $(PROG) run runs/mac_uniform.ini -q -o out/mac_uniform_$${u}_$$s.h5 \
	    --set mac.update=$$u --set mac.pressure_solver=$$s --set mac.u0=0.094 \
	    --set scene.output_every=1 >/dev/null; \
	done; done
	@set -e; for u in $(MAC_VARIANTS); do for s in direct relax; do \
	  $(PROG) run runs/mac_rest.ini -q -o out/mac_rest_homog_$${u}_$$s.h5 \
	    --set mac.update=$$u --set mac.pressure_solver=$$s \
	    --set mac.rho_amp=0 --set scene.output_every=1 >/dev/null; \
	done; done
	$(PROG) run runs/mac_uniform.ini -q -o out/mac_uniform_u01.h5 \
	    --set scene.output_every=1 >/dev/null
	$(PY) plots/fig_mac_checks.py -o out/mac_checks.png \
	    --rest $(foreach u,$(MAC_VARIANTS),$(foreach s,direct relax,"$(u), $(s)=out/mac_rest_$(u)_$(s).h5")) \
	    --homogeneous $(foreach u,$(MAC_VARIANTS),$(foreach s,direct relax,"$(u), $(s)=out/mac_rest_homog_$(u)_$(s).h5")) \
	    --uniform $(foreach u,$(MAC_VARIANTS),$(foreach s,direct relax,"$(u), $(s), u0 0.094=out/mac_uniform_$(u)_$(s).h5")) \
	    "consistent, direct, u0 0.1=out/mac_uniform_u01.h5"

# Yasuda Fig. 2: first-return maps, lower ball 1.2 g (A) and 0.8 g (B),
# MV2M for 1000 s with the Lyapunov estimate; first at the paper's
# dt = 1e-4 s, then at 1e-5 s (docs/models/balls.md says why both); then B at
# 1e-4 s in 100 s windows (the max z per window printed).  About 1 min.
FIG2_SET := --set lyapunov.enabled=yes
fig2: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/two_balls_A.ini -q -o out/fig2_A.h5 $(FIG2_SET)
	$(PROG) run runs/two_balls_B.ini -q -o out/fig2_B.h5 $(FIG2_SET)
	$(PROG) run runs/two_balls_A.ini -q -o out/fig2_A_dt1e-5.h5 $(FIG2_SET) \
	    --set scene.dt=1e-5 --set scene.output_every=1000
	$(PROG) run runs/two_balls_B.ini -q -o out/fig2_B_dt1e-5.h5 $(FIG2_SET) \
	    --set scene.dt=1e-5 --set scene.output_every=1000
	$(PY) plots/fig2_return_map.py out/fig2_A.h5 out/fig2_B.h5 \
	    out/fig2_A_dt1e-5.h5 out/fig2_B_dt1e-5.h5 -o out/fig2_return_map.png
	$(PY) plots/fig2_windows.py out/fig2_B.h5 -o out/fig2_B_windows.png

# Yasuda Fig. 3: lower ball 0.8 g with (A) Verlet 1e-4 s, (B) Verlet 1e-5 s,
# (C) RK4, (D) RK3, (E) implicit mid-point at 1e-4 s, 1000 s each.  RK3
# loses about 40% of the energy over the run; its energy bound is lifted
# so that the figure shows all of it.  About 1 min.
fig3: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/two_balls_B.ini -q -o out/fig3_A.h5 $(FIG2_SET) \
	    --set scene.integrator=verlet
	$(PROG) run runs/two_balls_B.ini -q -o out/fig3_B.h5 $(FIG2_SET) \
	    --set scene.integrator=verlet --set scene.dt=1e-5 \
	    --set scene.output_every=1000
	$(PROG) run runs/two_balls_B.ini -q -o out/fig3_C.h5 $(FIG2_SET) \
	    --set scene.integrator=rk4
	$(PROG) run runs/two_balls_B.ini -q -o out/fig3_D.h5 $(FIG2_SET) \
	    --set scene.integrator=rk3 --set scene.max_energy_error=0
	$(PROG) run runs/two_balls_B.ini -q -o out/fig3_E.h5 $(FIG2_SET) \
	    --set scene.integrator=impmid
	$(PY) plots/fig3_return_map.py out/fig3_A.h5 out/fig3_B.h5 out/fig3_C.h5 \
	    out/fig3_D.h5 out/fig3_E.h5 -o out/fig3_return_map.png
	$(PY) plots/fig2_windows.py out/fig3_E.h5 -o out/fig3_E_windows.png

# Yasuda Fig. 4: over 500-501 s, every step.  Each run stops at t = 500 s
# (--stop-after writes a checkpoint, exit 6) and continues with a row per
# step ([scene] output_every = 1) to 501 s.  The MV2M run also records the
# one-step difference Verlet - second-order mid-point ([compare]).
FIG4_SET := --set scene.t_end=501 --set compare.a=verlet
fig4: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/two_balls_B.ini -q -o out/fig4_mv2m.h5 $(FIG4_SET) \
	    --stop-after 5000000 || test $$? -eq 6
	$(PROG) run --restart out/fig4_mv2m.h5 -q --set scene.output_every=1
	$(PROG) run runs/two_balls_B.ini -q -o out/fig4_verlet.h5 $(FIG4_SET) \
	    --set scene.integrator=verlet --stop-after 5000000 || test $$? -eq 6
	$(PROG) run --restart out/fig4_verlet.h5 -q --set scene.output_every=1
	$(PY) plots/fig4_velocity_difference.py out/fig4_mv2m.h5 \
	    out/fig4_verlet.h5 -o out/fig4_velocity_difference.png

# Work-precision diagrams of `ballfilm converge` (acceptance runs of the
# integrator issues): the harmonic oscillator, the bouncing ball, the film
# (a kink with a density jump: a transient) and Greenspan's 1973 hexagon
# over a short window (docs/accuracy.md).
converge-figures: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) converge runs/harmonic.ini --methods verlet,mv2m,rk3,rk4,arkode \
	    -q -o out/converge_harmonic.h5
	$(PY) plots/work_precision.py out/converge_harmonic.h5 \
	    -o out/work_precision_harmonic.png
	$(PROG) converge runs/bouncing_ball.ini \
	    --methods verlet,mv2m,rk3,rk4,impmid,arkode -q \
	    -o out/converge_bouncing_ball.h5
	$(PY) plots/work_precision.py out/converge_bouncing_ball.h5 \
	    -o out/work_precision_bouncing_ball.png
	$(PROG) converge runs/bouncing_ball.ini \
	    --methods verlet,mv2m,rk3,rk4,impmid,arkode -q --t-end 1 \
	    --dt 1e-4,5e-5,2.5e-5,1.25e-5,6.25e-6 --tol 1e-6,1e-8,1e-10,1e-12 \
	    -o out/converge_bouncing_ball_1s.h5
	$(PY) plots/work_precision.py out/converge_bouncing_ball_1s.h5 \
	    -o out/work_precision_bouncing_ball_1s.png
	$(PROG) converge runs/kink_converge.ini \
	    --methods invariant,arkode,arkode-imex -q --t-end 1 \
	    --set film.perturbation=0 --set film.rho_d=1.2 \
	    --dt 1e-3,5e-4,2.5e-4,1.25e-4,6.25e-5 \
	    -o out/converge_film_transient.h5
	$(PY) plots/work_precision.py out/converge_film_transient.h5 \
	    -o out/work_precision_film_transient.png
	$(PROG) converge runs/greenspan73_hex_v50.ini \
	    --methods greenspan73,leapfrog,arkode -q --t-end 0.2 \
	    --dt 0.02,0.01,0.005,0.0025 -o out/converge_greenspan73.h5
	$(PY) plots/work_precision.py out/converge_greenspan73.h5 \
	    -o out/work_precision_greenspan73.png
	$(PROG) converge runs/coupled_fig8.ini \
	    --methods mv2m,rk4,mv2m:film_every=10,mv2m:film_every=auto -q \
	    --t-end 0.25 --dt 4e-5,2e-5,1e-5,5e-6 -o out/converge_coupled.h5
	$(PY) plots/work_precision.py out/converge_coupled.h5 --group q_d \
	    -o out/work_precision_coupled.png
# Yasuda Fig. 5: the perturbed kink, 1000 s at dt = 1e-3 s (10^6 steps),
# and the space-time picture of psi.
fig5: $(PROG) | deps deps-plot
	$(PROG) run runs/kink_steady.ini -q -o out/kink_steady.h5
	$(PY) plots/fig5_kink.py out/kink_steady.h5 -o out/fig5_kink.png
	$(PY) plots/film_spacetime.py out/kink_steady.h5 -o out/film_spacetime.png

# The kink's steady-state error for dx = 0.1, 0.05, 0.025 (falls as dx^2).
kink-dx2: $(PROG)
	@for dx in 0.1 0.05 0.025; do \
	  $(PROG) run runs/kink_converge.ini -q -o out/kink_dx$$dx.h5 \
	      --set film.dx=$$dx | sed -n "s/^film: kink error/dx = $$dx: kink error/p"; \
	done

# Yasuda Fig. 6: balls in the static kink potential (A: dt = 1e-4 s, B:
# 8e-4 s, C: peaks for 1e-4, 5.5e-4, 8e-4 s with an ensemble of shifted
# starts, D: one ball, 500 s).
KINK_ENS := 1e-12 1e-10 1e-8 1e-6 -1e-8
fig6: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/kink_balls_A.ini -q -o out/fig6_A.h5
	$(PROG) run runs/kink_balls_A.ini -q -o out/fig6_B.h5 --set scene.dt=8e-4
	$(PROG) run runs/kink_balls_A.ini -q -o out/fig6_C55.h5 --set scene.dt=5.5e-4
	$(PROG) run runs/kink_ball_D.ini -q -o out/fig6_D.h5
	@for dt in 5.5e-4 8e-4; do for d in $(KINK_ENS); do \
	  $(PROG) run runs/kink_balls_A.ini -q -o out/fig6_ens_$${dt}_$$d.h5 \
	    --set scene.dt=$$dt --set ball.2.position=$$(echo "0.2 + $$d" | \
	    $(PY) -c "import sys; print(repr(eval(sys.stdin.read())))") \
	    > /dev/null || exit 1; done; done
	$(PY) plots/fig6_kink_balls.py out/fig6_A.h5 out/fig6_B.h5 \
	    out/fig6_C55.h5 out/fig6_D.h5 out/fig6_ens_*.h5 -o out/fig6_kink_balls.png

# Yasuda Figs 8 and 9: four balls in the film, 50 s at dt = 1e-5 s
# (5e6 coupled steps each; the wall time is printed).
fig8: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/coupled_fig8.ini -q -o out/coupled_fig8.h5
	$(PY) plots/fig8_coupled.py out/coupled_fig8.h5 -o out/fig8_coupled.png

fig9: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/coupled_fig9.ini -q -o out/coupled_fig9.h5
	$(PY) plots/fig8_coupled.py out/coupled_fig9.h5 -o out/fig9_coupled.png

# Yasuda Fig. 9: a start scan for island chains (docs/models/coupled.md,
# "Start scan").  The outer balls at -X, +X for X = 0.40 .. 0.60 cm in
# steps of 0.0025 (81 starts, runs/start_scan.sh), at L = 50 and 50.1 cm,
# with the spline and the nodes quadrature, in the static kink for
# FIG9_SCAN_T s each with the Lyapunov estimate; fig9-confirm re-runs
# every second start found regular (the first, third, ... in X) and
# X = 0.5 cm with the dynamic film for FIG9_CONFIRM_T s; fig9-islands runs
# two confirmed starts, X = 0.48 and 0.5025 cm, with the dynamic film for
# FIG9_ISLANDS_T s at both lengths and draws their maps.  Reruns skip
# finished runs.
FIG9_SCAN_T ?= 20
FIG9_CONFIRM_T ?= 20
FIG9_ISLANDS_T ?= 100
FIG9_SET = --set lyapunov.enabled=yes --set scene.output_every=10000 \
	--set "film.profile_every=10 s"
FIG9_CASES = spline,50 spline,50.1 nodes,50 nodes,50.1
FIG9_SCENE = $$(if [ $$L = 50 ]; then echo runs/coupled_fig8.ini; \
	else echo runs/coupled_fig9.ini; fi)
FIG9_LABELS = $(foreach c,$(FIG9_CASES),"$(word 1,$(subst $(comma), ,$(c))), \
	L = $(word 2,$(subst $(comma), ,$(c))) cm=out/fig9_scan/$(1)_$(word 1,$(subst \
	$(comma), ,$(c)))_L$(word 2,$(subst $(comma), ,$(c)))")
comma := ,
fig9-scan: $(PROG) | deps deps-plot
	@mkdir -p out/fig9_scan
	@for c in $(FIG9_CASES); do q=$${c%,*}; L=$${c#*,}; \
	  runs/start_scan.sh $(PROG) $(FIG9_SCENE) out/fig9_scan/static_$${q}_L$$L \
	    0.40:0.0025:81 --set coupled.film=static --set coupling.quadrature=$$q \
	    --set scene.t_end=$(FIG9_SCAN_T) $(FIG9_SET) || exit 1; done
	$(PY) plots/fig9_scan.py $(call FIG9_LABELS,static) -o out/fig9_scan.png

fig9-confirm: $(PROG) | deps deps-plot
	@test -f out/fig9_scan/static_nodes_L50.1/regular.txt || \
	  $(MAKE) --no-print-directory fig9-scan
	@for c in $(FIG9_CASES); do q=$${c%,*}; L=$${c#*,}; \
	  l=out/fig9_scan/confirm_$${q}_L$$L.txt; \
	  { awk 'NR % 2 == 1' out/fig9_scan/static_$${q}_L$$L/regular.txt; \
	    echo 0.5000; } | sort -u > $$l; \
	  runs/start_scan.sh $(PROG) $(FIG9_SCENE) out/fig9_scan/dynamic_$${q}_L$$L @$$l \
	    --set coupling.quadrature=$$q --set scene.t_end=$(FIG9_CONFIRM_T) \
	    $(FIG9_SET) || exit 1; done
	$(PY) plots/fig9_scan.py $(call FIG9_LABELS,dynamic) -o out/fig9_confirm.png

fig9-islands: $(PROG) | deps deps-plot
	@mkdir -p out/fig9_scan
	@printf '0.4800\n0.5025\n' > out/fig9_scan/islands.txt
	@for L in 50 50.1; do \
	  runs/start_scan.sh $(PROG) $(FIG9_SCENE) out/fig9_scan/islands_L$$L \
	    @out/fig9_scan/islands.txt --set scene.t_end=$(FIG9_ISLANDS_T) \
	    --set scene.output_every=10000 --set "film.profile_every=10 s" \
	    || exit 1; done
	$(PY) plots/fig9_islands.py \
	    $(foreach L,50 50.1,$(foreach X,0.4800 0.5025,"L = $(L) cm, X = $(X) cm=out/fig9_scan/islands_L$(L)/x_$(X).h5")) \
	    -o out/fig9_islands.png

# Fig. 8C's offset of psi(0.3 cm), split: the paper's run from the analytic
# kink; the film alone (V0 = 0), i.e. the analytic kink relaxing on the
# grid; the balls in the film so relaxed (the discrete kink).  3 x 50 s.
fig8-offset: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/coupled_fig8.ini -q -o out/fig8_offset_kink.h5 >/dev/null
	$(PROG) run runs/coupled_fig8.ini -q -o out/fig8_offset_film.h5 \
	    --set coupling.V0=0 >/dev/null
	$(PROG) run runs/coupled_fig8.ini -q -o out/fig8_offset_discrete.h5 \
	    --set film.initial=file --set film.file=out/fig8_offset_film.h5 >/dev/null
	$(PY) plots/psi_offset.py \
	    "analytic kink, balls (Fig. 8)=out/fig8_offset_kink.h5" \
	    "analytic kink, no coupling (V0 0)=out/fig8_offset_film.h5" \
	    "discrete kink, balls=out/fig8_offset_discrete.h5"

# The same with [coupled] symmetrize = yes (forced mirror symmetry), the
# test of docs/models/coupled.md's explanation of the scattered maps (~1.6x the cost).
fig8-sym: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/coupled_fig8_sym.ini -q -o out/coupled_fig8_sym.h5
	$(PY) plots/fig8_coupled.py out/coupled_fig8_sym.h5 -o out/fig8_coupled_sym.png

fig9-sym: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) run runs/coupled_fig9_sym.ini -q -o out/coupled_fig9_sym.h5
	$(PY) plots/fig8_coupled.py out/coupled_fig9_sym.h5 -o out/fig9_coupled_sym.png

# Sensitivity inside the symmetric subspace: the symmetrized runs again
# for 20 s with the outer balls moved out by 1e-10 cm (symmetrically).
sym-divergence: $(PROG) | deps deps-plot
	@mkdir -p out
	@test -f out/coupled_fig8_sym.h5 || $(MAKE) --no-print-directory fig8-sym
	@test -f out/coupled_fig9_sym.h5 || $(MAKE) --no-print-directory fig9-sym
	for L in 8 9; do $(PROG) run runs/coupled_fig$${L}_sym.ini -q \
	    -o out/coupled_fig$${L}_sym_pert.h5 --set scene.t_end=20 \
	    --set ball.1.position=-0.5000000001 \
	    --set ball.4.position=0.5000000001 || exit 1; done
	$(PY) plots/sym_divergence.py out/coupled_fig8_sym.h5 \
	    out/coupled_fig8_sym_pert.h5 out/coupled_fig9_sym.h5 \
	    out/coupled_fig9_sym_pert.h5 -o out/sym_divergence.png

# Multirate option against the single-rate run (Fig. 8 scene, 0-1 s).
MR_K := 3 10 30 100 300
multirate: $(PROG) | deps deps-plot
	@mkdir -p out
	@rm -f out/multirate_times.txt
	@w=$$($(PROG) run runs/coupled_fig8.ini -q -o out/mr_ref.h5 --set scene.t_end=1 \
	    | sed -n 's/^wall time: *\([0-9.]*\) s.*/\1/p'); \
	  echo "single out/mr_ref.h5 $$w" >> out/multirate_times.txt
	@w=$$($(PROG) run runs/coupled_fig8.ini -q -o out/mr_half.h5 --set scene.t_end=1 \
	    --set scene.dt=5e-6 --set scene.output_every=200 \
	    | sed -n 's/^wall time: *\([0-9.]*\) s.*/\1/p'); \
	  echo "half out/mr_half.h5 $$w" >> out/multirate_times.txt
	@for k in $(MR_K); do \
	  w=$$($(PROG) run runs/coupled_fig8.ini -q -o out/mr_$$k.h5 --set scene.t_end=1 \
	    --set coupled.film_every=$$k | sed -n 's/^wall time: *\([0-9.]*\) s.*/\1/p'); \
	  echo "film_every=$$k out/mr_$$k.h5 $$w" >> out/multirate_times.txt; done
	$(PY) plots/multirate.py out/multirate_times.txt -o out/multirate.png

# Observed orders of the film scheme in dx and in dt (docs/models/film.md).
film-orders: $(BUILD)/bench/film_orders
	$(BUILD)/bench/film_orders
# Greenspan 1972, Example 1 (Figs 3.1-3.9) and the heights of the heavy
# particles.
fig-g72-ex1: $(PROG) | deps deps-plot
	$(PROG) run runs/greenspan72_ex1.ini -q -o out/g72_ex1.h5
	$(PY) plots/fig_g72_ex1.py out/g72_ex1.h5 -o out/fig_g72_ex1.png \
	    --heights out/fig_g72_ex1_heights.png

# Example 1's claim (complete interchange by step 2080) over 100 runs whose
# printed initial velocities are perturbed within their rounding (+-0.005),
# for the text's reading and for the listing's (cutoff 2d, WALCOL, EPS).
G72_ENS := $(shell seq 1 100)
fig-g72-ex1-ensemble: $(PROG) | deps deps-plot
	@mkdir -p out/g72_ens
	@for k in $(G72_ENS); do \
	  $(PROG) run runs/greenspan72_ex1.ini -q -o out/g72_ens/text_$$k.h5 \
	    --set greenspan72.perturb=0.005 --set greenspan72.perturb_seed=$$k \
	    --set greenspan72.output=diagnostics --set scene.output_every=10 \
	    >/dev/null || exit 1; \
	  $(PROG) run runs/greenspan72_ex1.ini -q -o out/g72_ens/listing_$$k.h5 \
	    --set greenspan72.perturb=0.005 --set greenspan72.perturb_seed=$$k \
	    --set greenspan72.output=diagnostics --set scene.output_every=10 \
	    --set repulsion.cutoff=40 --set walls.rule=fortran \
	    --set support.eps=1e-3 >/dev/null || exit 1; \
	done
	$(PY) plots/g72_ensemble.py out/g72_ens/text_*.h5 --label "(text)" \
	    -o out/fig_g72_ex1_ensemble_text.png \
	    --table out/g72_ex1_ensemble_text.txt
	$(PY) plots/g72_ensemble.py out/g72_ens/listing_*.h5 \
	    --label "(listing: cutoff 2d, WALCOL, EPS)" \
	    -o out/fig_g72_ex1_ensemble_listing.png \
	    --table out/g72_ex1_ensemble_listing.txt

# Example 2: Figs 3.10-3.14 in both readings of t_k, and the diagnostics
# over 30000 steps.
fig-g72-ex2: $(PROG) | deps deps-plot
	$(PROG) run runs/greenspan72_ex2.ini -q -o out/g72_ex2_short.h5 \
	    --set scene.t_end=3 --set scene.output_every=1
	$(PROG) run runs/greenspan72_ex2.ini -q -o out/g72_ex2.h5
	$(PY) plots/fig_g72_ex2.py out/g72_ex2_short.h5 out/g72_ex2.h5 \
	    -o out/fig_g72_ex2.png --long-output out/fig_g72_ex2_long.png \
	    --diag out/fig_g72_ex2_diag.png

# 200704 particles for 3000 steps (several minutes).
fig-g72-large: $(PROG) | deps deps-plot
	$(PROG) run runs/greenspan72_large.ini -q -o out/g72_large.h5
	$(PY) plots/fig_g72_large.py out/g72_large.h5 -o out/fig_g72_large.png

# Greenspan 1973, Figs 3.2-3.5: the hexagonal flows at V = 50, 300, 1000;
# V = 1000 also at dt = 0.01 (omega = 1 converges only for dt <= 0.01) and
# with step halving from dt = 0.1.
fig-g73-hex: $(PROG) | deps deps-plot
	$(PROG) run runs/greenspan73_hex_v50.ini -q -o out/g73_hex_v50.h5
	$(PROG) run runs/greenspan73_hex_v300.ini -q -o out/g73_hex_v300.h5
	$(PROG) run runs/greenspan73_hex_v1000.ini -q -o out/g73_hex_v1000.h5
	$(PROG) run runs/greenspan73_hex_v1000.ini -q -o out/g73_hex_v1000_dt01.h5 \
	    --set scene.dt=0.01 --set greenspan73.omega=1
	$(PROG) run runs/greenspan73_hex_v1000.ini -q -o out/g73_hex_v1000_halve.h5 \
	    --set greenspan73.omega=1 --set greenspan73.on_failure=halve
	$(PY) plots/fig_g73_hex.py out/g73_hex_v50.h5 -o out/fig_g73_3_2.png \
	    --times 0.2 0.4 0.6 0.8 1.0 1.2 1.4 --label " (Fig. 3.2)"
	$(PY) plots/fig_g73_hex.py out/g73_hex_v300.h5 -o out/fig_g73_3_3_3_4.png \
	    --directions --label " (Figs 3.3, 3.4)"
	$(PY) plots/fig_g73_hex.py out/g73_hex_v1000.h5 -o out/fig_g73_3_5.png \
	    --compare out/g73_hex_v1000_dt01.h5 --label ", omega = 0.2 (Fig. 3.5)"

# Greenspan 1973, Figs 3.7-3.8 (friction) and 3.10 (penetration), in the
# readings of the text and of the listing; prints P1 at step 25.
G73_PEN = $(PROG) run runs/greenspan73_penetration.ini -q
fig-g73-wall: $(PROG) | deps deps-plot
	$(PROG) run runs/greenspan73_wall_friction.ini -q -o out/g73_friction_listing.h5
	$(PROG) run runs/greenspan73_wall_friction.ini -q -o out/g73_friction_text.h5 \
	    --set greenspan73.mass=paper --set greenspan73.wall_mass=10
	$(G73_PEN) -o out/g73_pen_listing.h5
	$(G73_PEN) -o out/g73_pen_listing_gall.h5 --set greenspan73.gravity=all
	$(G73_PEN) -o out/g73_pen_text.h5 --set greenspan73.mass=paper \
	    --set greenspan73.wall_mass=10 --set greenspan73.gravity=all
	$(G73_PEN) -o out/g73_pen_text_m1.h5 --set greenspan73.mass=paper \
	    --set greenspan73.wall_mass=1
	$(G73_PEN) -o out/g73_pen_listing_m10.h5 --set greenspan73.wall_mass=10
	$(G73_PEN) -o out/g73_pen_fixed28.h5 --set greenspan73.fixed="2 8"
	$(PY) plots/fig_g73_wall.py --friction out/g73_friction_listing.h5 \
	    out/g73_friction_text.h5 -o out/fig_g73_3_7_3_8.png
	$(PY) plots/fig_g73_wall.py --penetration out/g73_pen_listing.h5 \
	    out/g73_pen_listing_gall.h5 out/g73_pen_fixed28.h5 \
	    out/g73_pen_listing_m10.h5 out/g73_pen_text_m1.h5 \
	    out/g73_pen_text.h5 -o out/fig_g73_3_10.png \
	    --table out/g73_penetration.txt

# One short movie per model (ballfilm animate, 100 frames at 20 fps), from
# short runs: out/movies/NAME.mp4 beside NAME.h5 and NAME.xmf.
MOVIE_DIR := out/movies
MOVIE_ARGS := --frames 100 --fps 20
define movie
	$(PROG) run $(2) -q -o $(MOVIE_DIR)/$(1).h5 $(3) > /dev/null
	$(PROG) animate $(MOVIE_DIR)/$(1).h5 -o $(MOVIE_DIR)/$(1).mp4 $(MOVIE_ARGS)
endef
movies: $(PROG) | deps deps-movies
	@mkdir -p $(MOVIE_DIR)
	$(call movie,balls,runs/two_balls_B.ini,--set scene.t_end=20)
	$(call movie,film,runs/kink_steady.ini,--set scene.t_end=20 \
	    --set "scene.output_every=0.2 s" --set "film.profile_every=0.2 s" \
	    --set film.perturbation=0.05)
	$(call movie,coupled,runs/coupled_fig8.ini,--set scene.t_end=1 \
	    --set "film.profile_every=0.01 s")
	$(call movie,greenspan72,runs/greenspan72_ex2.ini,--set scene.t_end=20 \
	    --set scene.output_every=20)
	$(call movie,greenspan73_hex,runs/greenspan73_hex_v300.ini, \
	    --set scene.t_end=2)
	$(call movie,greenspan73_wall,runs/greenspan73_wall_friction.ini,)
	$(call movie,mac,runs/stratres.ini,--set scene.output_every=2)
	@echo "movies are in $(MOVIE_DIR)/"

figures:
	@$(MAKE) --no-print-directory deps deps-plot
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory fig1
	@$(MAKE) --no-print-directory fig2
	@$(MAKE) --no-print-directory fig3
	@$(MAKE) --no-print-directory fig4
	@$(MAKE) --no-print-directory converge-figures
	@$(MAKE) --no-print-directory survey-mass
	@$(MAKE) --no-print-directory survey-length
	@$(MAKE) --no-print-directory fig-vibrating-table
	@$(MAKE) --no-print-directory stratres
	@$(MAKE) --no-print-directory mac-checks
	@$(MAKE) --no-print-directory fig5
	@$(MAKE) --no-print-directory kink-dx2
	@$(MAKE) --no-print-directory fig6
	@$(MAKE) --no-print-directory multirate
	@$(MAKE) --no-print-directory fig8
	@$(MAKE) --no-print-directory fig9
	@$(MAKE) --no-print-directory fig8-sym
	@$(MAKE) --no-print-directory fig9-sym
	@$(MAKE) --no-print-directory fig9-islands
	@$(MAKE) --no-print-directory sym-divergence
	@$(MAKE) --no-print-directory fig-g72-ex1 fig-g72-ex1-ensemble \
	    fig-g72-ex2 fig-g72-large fig-g73-hex fig-g73-wall
	@echo "figures are in out/"

# Survey (the paper's "issue for further study"): two falling balls, upper
# ball 1 g, lower ball 0.5..2 g in 64 steps, MV2M at dt = 1e-4 s over 200 s
# each, with the Lyapunov exponent and the return map's fill fraction.
# Runs on both cores (--jobs 2); rerunning skips finished cases.
survey-mass: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) sweep runs/two_balls_A.ini --vary ball.1.mass=0.5:2.0:64 \
	    --set scene.t_end=200 --set lyapunov.enabled=yes \
	    --set scene.output_every=10000 --jobs 2 -q -o out/survey_mass
	$(PY) plots/survey.py out/survey_mass -o out/survey_mass.png \
	    --label "lower/upper mass ratio"

# Survey of the coupled film: the fourth ball's return map and the largest
# Lyapunov exponent (shadow coupled system, docs/models/coupled.md) over film lengths
# 49.5..50.5 cm (11 points), 50 s each with the multirate option (film step
# every 30 ball steps, which passed its accuracy check: docs/models/coupled.md, Multirate).
# SURVEY_T: simulated seconds per length (50 s is the paper's Figs 8-9;
# the Lyapunov estimates need longer to settle).
SURVEY_T ?= 200
survey-length: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) sweep runs/coupled_fig8.ini --vary film.length=49.5:50.5:11 \
	    --set scene.t_end=$(SURVEY_T) \
	    --set coupled.film_every=30 --set scene.output_every=1000 \
	    --set "film.profile_every=10 s" --set lyapunov.enabled=yes \
	    --jobs 2 -q -o out/survey_length_$(SURVEY_T)s
	$(PY) plots/survey.py out/survey_length_$(SURVEY_T)s -o out/survey_length.png \
	    --label "film length [cm]" --maps 11

# The ball on a vibrating table (docs/models/vibrating_table.md): the
# bifurcation diagram of the impact phase over Gamma = 1.0-3.2, 221 cases of
# runs/vibrating_table.ini (5 s each) over [floor] amplitude on both cores
# (rerunning skips finished cases), the scene once, the exact hard-impact
# map and the theory's thresholds: 3.0 min of CPU (`time make fig-vibrating-table`).
fig-vibrating-table: $(PROG) | deps deps-plot
	@mkdir -p out
	$(PROG) sweep runs/vibrating_table.ini --vary floor.amplitude=0.062:0.1986:221 \
	    --set "scene.output_every=0.1 s" --jobs 2 -q -o out/vibrating_table_sweep
	$(PROG) run runs/vibrating_table.ini -q -o out/vibrating_table.h5
	$(PY) plots/vibrating_table.py out/vibrating_table_sweep \
	    out/vibrating_table.h5 -o out/vibrating_table.png

# ---------------------------------------------------------------- tests
# A kill at a chosen write of HDF5 (tests/killwrite.c), preloaded into the
# program by test_h5out.c; without sanitizers whatever the build, since it
# is loaded before their runtime.
KILLWRITE := $(BUILD)/tests/killwrite.so
$(KILLWRITE): tests/killwrite.c
	@mkdir -p $(dir $@)
	$(CC) $(CSTD) -shared -fPIC -o $@ $<

build-tests: $(PROG) $(RUNNER) $(MPI_PROG) $(KILLWRITE)

# Tests get the program, the repository and the compiler flags (the
# fp-contract test compiles a probe with them).
TEST_ENV = BALLFILM_ROOT=$(CURDIR) BALLFILM_CC="$(CC)" \
           BALLFILM_CFLAGS="$(CSTD) $(SANITIZE)" \
           BALLFILM_KILLWRITE=$(abspath $(KILLWRITE))

test-run: build-tests
	$(TEST_ENV) BALLFILM_BIN=$(abspath $(PROG)) \
	  BALLFILM_MPI_BIN=$(abspath $(MPI_PROG)) CK_DEFAULT_TIMEOUT=600 $(RUNNER)

test:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory test-static
	@$(MAKE) --no-print-directory test-run
	@$(MAKE) --no-print-directory test-movies
	@$(MAKE) --no-print-directory test-xdmf
	@$(MAKE) --no-print-directory test-units
	@$(MAKE) --no-print-directory test-export
	@$(MAKE) --no-print-directory test-install
	@$(MAKE) --no-print-directory test-examples
	@$(MAKE) --no-print-directory test-python
	@$(MAKE) --no-print-directory test-pip
	@$(MAKE) --no-print-directory test-notebooks
	@$(MAKE) --no-print-directory test-cli-docs

# The code's layering against docs/architecture.md (include directions,
# circles, public headers, file sizes, who reads scenes) and the docs'
# links (every relative link resolves; nothing tracked points outside the
# repository).
test-static:
	$(PY) tests/check_architecture.py
	$(PY) tests/check_docs.py

# Movies of every model (ffprobe counts frames and sizes; the GIF fallback
# without ffmpeg) and the XDMF sidecars in ParaView (pvpython against
# h5py); the packages are installed when run as root.
test-movies: $(PROG) | deps-movies
	$(PY) tests/test_movies.py $(PROG) build/test-movies

test-xdmf: $(PROG) | deps-xdmf
	$(PY) tests/test_xdmf.py $(PROG) build/test-xdmf

# Every unit of a run of each model parses with UDUNITS-2, and
# docs/output.md documents every dataset with its unit.
test-units: $(PROG) | deps-units
	$(PY) tests/test_units.py $(PROG) build/test-units

# `ballfilm export`: H5MD read with h5py and MDAnalysis, extended XYZ read
# with ASE, against the runs' files, and its refusals (tests/
# test_export.py); MDAnalysis and ASE are installed when run as root.
test-export: $(PROG) | deps-export
	$(PY) tests/test_export.py $(PROG) $(BUILD)/test-export

# The library as its users get it (docs/library.md): make install into a
# fresh temporary prefix, an example compiled with pkg-config alone
# (shared and static), the .so's exports, the installed Python package,
# the installed scenes, `ballfilm animate` and a figure script run from the
# prefix, make uninstall (tests/test_install.py).
test-install: $(PROG) $(LIB) $(SHLIB) | deps-install deps-movies
	$(PY) tests/test_install.py

# Every example of examples/ built with pkg-config against an install into
# build/prefix and run briefly (each checks its own trust numbers), and
# the vibrating floor's return map drawn by its plot script.
EXAMPLES_RUN := $(BUILD)/examples
test-examples: $(PROG) $(LIB) $(SHLIB) | deps-install deps-plot
	@$(MAKE) --no-print-directory install PREFIX=$(CURDIR)/$(BUILD)/prefix >/dev/null
	rm -rf $(EXAMPLES_RUN)
	PKG_CONFIG_PATH=$(CURDIR)/$(BUILD)/prefix/lib/pkgconfig \
	  $(MAKE) --no-print-directory -C examples O=$(CURDIR)/$(EXAMPLES_RUN) run
	$(PY) plots/vibrating_floor_map.py $(EXAMPLES_RUN)/vibrating_floor.h5 \
	  -o $(EXAMPLES_RUN)/vibrating_floor_map.png

# The Python package (python/ballfilm) with pytest against the library of
# this build (tests/python/).
PY_TEST_PKGS := python3-pytest python3-numpy python3-h5py
deps-python:
	$(call need_pkgs,$(PY_TEST_PKGS))

test-python: $(PROG) $(SHLIB) $(KILLWRITE) | deps-python
	BALLFILM_BIN=$(abspath $(PROG)) BALLFILM_LIB=$(abspath $(SHLIB)) \
	  BALLFILM_KILLWRITE=$(abspath $(KILLWRITE)) \
	  $(PY) -m pytest -q -p no:cacheprovider tests/python

# The package installed by pip, offline, into fresh virtual environments
# (pyproject.toml: the build runs make shared and puts the library, the
# scenes and the plot scripts inside the package), then used from outside
# the repository with no variables; and pip install -e (tests/test_pip.py).
PIP_PKGS := python3-pip python3-setuptools python3-wheel python3-venv \
            python3-numpy python3-h5py
deps-pip:
	$(call need_pkgs,$(PIP_PKGS))

test-pip: $(SHLIB) | deps-pip
	$(PY) tests/test_pip.py

# Every notebook of examples/notebooks/ executed with Debian's nbclient and
# ipykernel against this build (each ends by asserting its trust numbers;
# a notebook committed with outputs fails; tests/test_notebooks.py).
NB_PKGS := python3-nbclient python3-ipykernel python3-nbformat \
           python3-numpy python3-h5py python3-matplotlib
deps-notebooks:
	$(call need_pkgs,$(NB_PKGS))

test-notebooks: $(SHLIB) | deps-notebooks
	$(PY) tests/test_notebooks.py

# The man page as man-db shows it (every section, every option of every
# command's --help) and the bash completion run in bash (a command, an
# option, a scene key): tests/test_cli_docs.py.
CLI_DOC_PKGS := man-db bsdextrautils
deps-cli-docs:
	$(call need_pkgs,$(CLI_DOC_PKGS))

test-cli-docs: $(PROG) $(MAN) | deps-cli-docs
	$(PY) tests/test_cli_docs.py $(PROG) $(MAN) src/cli/ballfilm.bash

# ASAN_LEAKS=0 turns off LeakSanitizer only (for containers that forbid
# the ptrace it needs; .ci/run decides this by a probe and says so).
ASAN_LEAKS ?= 1
CHECK_SAN := -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
check:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory BUILD=build/asan BINDIR=build/asan/bin \
	  SANITIZE="$(CHECK_SAN)" build-tests
	ASAN_OPTIONS=detect_leaks=$(ASAN_LEAKS):abort_on_error=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	$(TEST_ENV) BALLFILM_BIN=$(CURDIR)/build/asan/bin/ballfilm \
	BALLFILM_MPI_BIN=$(CURDIR)/build/asan/bin/ballfilm-mpi \
	BALLFILM_SANITIZED=1 CK_DEFAULT_TIMEOUT=3000 build/asan/tests/runner

# ---------------------------------------------------------------- valgrind
# Every scene of runs/ for a few steps under valgrind: no invalid access,
# no definite leak (memcheck), exit status 1 otherwise.
valgrind: $(PROG)
	@command -v valgrind >/dev/null || { echo "make valgrind needs: apt-get install -y valgrind"; exit 1; }
	@mkdir -p build/valgrind
	@set -e; for s in runs/*.ini; do \
	  n=$$(basename $$s .ini); echo "== $$n"; \
	  valgrind -q --error-exitcode=1 --leak-check=full \
	    --errors-for-leak-kinds=definite --show-leak-kinds=definite \
	    $(PROG) run $$s -q -o build/valgrind/$$n.h5 --stop-after 20 \
	    > build/valgrind/$$n.log 2>&1 || { rc=$$?; \
	    if [ $$rc -ne 6 ] && [ $$rc -ne 0 ]; then cat build/valgrind/$$n.log; exit 1; fi; }; \
	done; echo "valgrind: all scenes clean"

# ---------------------------------------------------------------- fuzz
# libFuzzer on the scene parser and validation (tests/fuzz_one.c), seeded
# with the scenes of runs/ (not the 200704-particle one: valid, but each of
# its runs takes seconds under the sanitizers), for FUZZ_SECONDS; then on
# checkpoints (tests/fuzz_ckpt.c: a real checkpoint of every model damaged
# or edited, the restart must refuse it cleanly or run on), seeded with
# tests/fuzz/ckpt_corpus, for FUZZ_CKPT_SECONDS.  Findings go to
# build/fuzz/crashes and build/fuzz/ckpt_crashes.  Copy every crash input
# into tests/fuzz/regress/ or tests/fuzz/ckpt_regress/ (the test suite
# replays them; make test also runs a bounded deterministic set of
# checkpoint damages and edits).  Last, fuzz-h5 for FUZZ_H5_SECONDS.
FUZZ_SECONDS ?= 600
FUZZ_CKPT_SECONDS ?= 300
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=undefined -g
fuzz:
	@$(MAKE) --no-print-directory deps
	@command -v clang >/dev/null || { echo "make fuzz needs clang: apt-get install -y clang libclang-rt-14-dev"; exit 1; }
	@$(MAKE) --no-print-directory CC=clang BUILD=build/fuzz BINDIR=build/fuzz/bin \
	  SANITIZE="$(FUZZ_SAN) -fsanitize=fuzzer-no-link" build/fuzz/libballfilm.a
	clang $(CPPFLAGS) -Itests $(CSTD) $(FUZZ_SAN) -fsanitize=fuzzer \
	  tests/fuzz/fuzz_scene.c tests/fuzz_one.c build/fuzz/libballfilm.a \
	  $(LDLIBS) -o build/fuzz/fuzz_scene
	clang $(CPPFLAGS) -Itests $(CSTD) $(FUZZ_SAN) -fsanitize=fuzzer \
	  tests/fuzz/fuzz_checkpoint.c tests/fuzz_ckpt.c build/fuzz/libballfilm.a \
	  $(LDLIBS) -o build/fuzz/fuzz_checkpoint
	@mkdir -p build/fuzz/corpus build/fuzz/crashes build/fuzz/ckpt_corpus \
	  build/fuzz/ckpt_crashes
	for f in runs/*.ini; do case $$f in *_large.ini) ;; \
	  *) cp -n $$f tests/fuzz/corpus/ ;; esac; done
	build/fuzz/fuzz_scene build/fuzz/corpus tests/fuzz/corpus \
	  -dict=tests/fuzz/scene.dict -max_total_time=$(FUZZ_SECONDS) \
	  -rss_limit_mb=4096 -timeout=20 -max_len=4096 \
	  -artifact_prefix=build/fuzz/crashes/ -print_final_stats=1
	BALLFILM_ROOT=$(CURDIR) build/fuzz/fuzz_checkpoint build/fuzz/ckpt_corpus \
	  tests/fuzz/ckpt_corpus -max_total_time=$(FUZZ_CKPT_SECONDS) \
	  -rss_limit_mb=4096 -timeout=60 -max_len=512 \
	  -artifact_prefix=build/fuzz/ckpt_crashes/ -print_final_stats=1
	@$(MAKE) --no-print-directory fuzz-h5

# The readers of output files at random (tests/fuzz/fuzz_h5.c): real
# outputs of every model (made in build/fuzz/h5_corpus), one to three
# random mutations of HDF5 objects, given to info, xdmf, run --restart or
# [film] initial = file of the program of make check (ASan + UBSan) under
# CPU, file-size and wall-clock limits, for FUZZ_H5_SECONDS.  It prints
# its seed; FUZZ_H5_SEED=S replays that sequence.  Each finding (a signal,
# a limit, an exit status outside 0-6, a sanitizer report, a refusal not
# naming its file) is a recipe line in build/fuzz/h5_crashes/found-S.recipes;
# fix the reader, then copy the file into tests/fuzz/h5_regress/ (the
# suite hostile_read replays it).  Exit status 1 when something was found.
FUZZ_H5_SECONDS ?= 300
FUZZ_H5_SEED ?=
fuzz-h5:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory BUILD=build/asan BINDIR=build/asan/bin \
	  SANITIZE="$(CHECK_SAN)" build/asan/bin/ballfilm
	@mkdir -p build/fuzz
	$(CC) $(CPPFLAGS) -Itests $(CSTD) tests/fuzz/fuzz_h5.c tests/fuzz_h5.c \
	  $(LDLIBS) -o build/fuzz/fuzz_h5
	ASAN_OPTIONS=detect_leaks=$(ASAN_LEAKS):abort_on_error=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	BALLFILM_ROOT=$(CURDIR) BALLFILM_BIN=$(CURDIR)/build/asan/bin/ballfilm \
	BALLFILM_SANITIZED=1 FUZZ_H5_SECONDS=$(FUZZ_H5_SECONDS) \
	FUZZ_H5_SEED=$(FUZZ_H5_SEED) \
	  build/fuzz/fuzz_h5 build/fuzz/h5_corpus build/fuzz/h5_crashes

# ---------------------------------------------------------------- bench
# bench/plain_*.c are yardsticks: programs without the library that the
# scripts bench/*_vs_plain.sh run with their arguments beside ballfilm.
# bench/support_ab.sh REV is a tool for work on the support gravity (it
# needs a revision to compare with), not one of the benchmarks.
bench:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory all mpi $(BENCH_BIN)
	@for b in $(filter-out $(BUILD)/bench/plain_%,$(BENCH_BIN)); do \
	  echo "== $$b"; BALLFILM_ROOT=$(CURDIR) $$b || exit 1; done
	@for b in $(filter-out bench/support_ab.sh,$(wildcard bench/*.sh)); do \
	  echo "== $$b"; $$b || exit 1; done

clean:
	rm -rf build bin
