# ballfilm: balls and particle fluids in thin liquid films.
#
#   make run       install missing packages, build, run the default scene,
#                  draw its figure (out/)
#   make test      build and run the test suite
#   make check     the test suite under AddressSanitizer + UBSan
#   make figures   every paper figure (long runs; see README)
#   make bench     performance measurements (ratios measured in one run)
#   make clean
#
# Debian 12 packages are installed automatically when run as root; otherwise
# the exact apt-get line is printed.

SHELL := /bin/bash
.DEFAULT_GOAL := all

BUILD_PKGS := gcc make pkg-config libsundials-dev libgsl-dev libhdf5-dev \
              hdf5-tools libinih-dev check
PLOT_PKGS  := python3-numpy python3-matplotlib python3-h5py
PY         := /usr/bin/python3

# ---------------------------------------------------------------- flags
BUILD   ?= build
BINDIR  ?= bin
SANITIZE ?=
GIT     := $(shell git rev-parse --short HEAD 2>/dev/null || echo unknown)

CC       = gcc
CSTD     = -std=c11 -O2 -Wall -Wextra -Werror -ffp-contract=off
CPPFLAGS = -Iinclude -Isrc/cli -D_POSIX_C_SOURCE=200809L -DBF_GIT='"$(GIT)"' \
           $(shell pkg-config --cflags hdf5-serial gsl 2>/dev/null)
CFLAGS   = $(CSTD) $(SANITIZE) -MMD -MP
LDLIBS   = $(shell pkg-config --libs hdf5-serial 2>/dev/null) -lhdf5_hl \
           -lsundials_arkode -lsundials_nvecserial -linih \
           $(shell pkg-config --libs gsl 2>/dev/null) -lm -fopenmp
LDFLAGS  = $(SANITIZE)
CHECK_CFLAGS = $(shell pkg-config --cflags check 2>/dev/null)
CHECK_LIBS   = $(shell pkg-config --libs check 2>/dev/null)

# ---------------------------------------------------------------- sources
LIB_SRC  := $(sort $(filter-out src/cli/%,$(wildcard src/*/*.c)))
CLI_SRC  := $(sort $(wildcard src/cli/*.c))
TEST_SRC := $(sort $(wildcard tests/test_*.c))
TEST_AUX := $(sort $(filter-out tests/test_%,$(wildcard tests/*.c)))
BENCH_SRC := $(sort $(wildcard bench/*.c))

LIB_OBJ   := $(LIB_SRC:%.c=$(BUILD)/obj/%.o)
CLI_OBJ   := $(CLI_SRC:%.c=$(BUILD)/obj/%.o)
TEST_OBJ  := $(TEST_SRC:%.c=$(BUILD)/obj/%.o) $(TEST_AUX:%.c=$(BUILD)/obj/%.o)
BENCH_BIN := $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%)
LIB       := $(BUILD)/libballfilm.a
PROG      := $(BINDIR)/ballfilm
RUNNER    := $(BUILD)/tests/runner

.PHONY: all run test check figures bench clean deps deps-plot test-run \
        build-tests fig1 fig-g72-ex1 fig-g72-ex1-ensemble fig-g72-ex2 \
        fig-g72-large fig-g73-hex fig-g73-wall

all: $(PROG)

$(BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@

$(BUILD)/obj/tests/%.o: tests/%.c $(BUILD)/tests/suites.inc
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) -I$(BUILD)/tests $(CHECK_CFLAGS) $(CFLAGS) -c $< -o $@

# OpenMP (libgomp, part of gcc) only where it pays: the particle forces.
# Their results do not depend on the number of threads (tested).
OMP_OBJ := $(addprefix $(BUILD)/obj/,src/particles/support.o \
             src/particles/repulsion.o src/models/greenspan72.o)
$(OMP_OBJ): CFLAGS += -fopenmp

$(LIB): $(LIB_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	ar rcs $@ $^

$(PROG): $(CLI_OBJ) $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) -o $@ $(CLI_OBJ) $(LIB) $(LDLIBS)

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

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)

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

# ---------------------------------------------------------------- main job
run:
	@$(MAKE) --no-print-directory deps deps-plot
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory fig1
	@echo
	@echo "results:  out/bouncing_ball_verlet.h5  out/bouncing_ball_mv2m.h5"
	@echo "figure:   out/fig1_phase.png"

# Yasuda Fig. 1: the bouncing ball, Verlet beside MV2M (dt = 3e-4 s, 100 s).
fig1: $(PROG)
	@mkdir -p out
	$(PROG) run runs/bouncing_ball.ini -q -o out/bouncing_ball_verlet.h5 \
	    --set scene.integrator=verlet
	$(PROG) run runs/bouncing_ball.ini -q -o out/bouncing_ball_mv2m.h5 \
	    --set scene.integrator=mv2m
	$(PY) plots/fig1_phase.py out/bouncing_ball_verlet.h5 \
	    out/bouncing_ball_mv2m.h5 -o out/fig1_phase.png

# Greenspan 1972, Example 1 (Figs 3.1-3.9) and the heights of the heavy
# particles.
fig-g72-ex1: $(PROG)
	@mkdir -p out
	$(PROG) run runs/greenspan72_ex1.ini -q -o out/g72_ex1.h5
	$(PY) plots/fig_g72_ex1.py out/g72_ex1.h5 -o out/fig_g72_ex1.png \
	    --heights out/fig_g72_ex1_heights.png

# Example 1's claim (complete interchange by step 2080) over 100 runs whose
# printed initial velocities are perturbed within their rounding (+-0.005),
# for the text's reading and for the listing's (cutoff 2d, WALCOL, EPS).
G72_ENS := $(shell seq 1 100)
fig-g72-ex1-ensemble: $(PROG)
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
fig-g72-ex2: $(PROG)
	@mkdir -p out
	$(PROG) run runs/greenspan72_ex2.ini -q -o out/g72_ex2_short.h5 \
	    --set scene.t_end=3 --set scene.output_every=1
	$(PROG) run runs/greenspan72_ex2.ini -q -o out/g72_ex2.h5
	$(PY) plots/fig_g72_ex2.py out/g72_ex2_short.h5 out/g72_ex2.h5 \
	    -o out/fig_g72_ex2.png --long-output out/fig_g72_ex2_long.png \
	    --diag out/fig_g72_ex2_diag.png

# 200704 particles for 3000 steps (several minutes).
fig-g72-large: $(PROG)
	@mkdir -p out
	$(PROG) run runs/greenspan72_large.ini -q -o out/g72_large.h5
	$(PY) plots/fig_g72_large.py out/g72_large.h5 -o out/fig_g72_large.png

# Greenspan 1973, Figs 3.2-3.5: the hexagonal flows at V = 50, 300, 1000;
# V = 1000 also at dt = 0.01 (omega = 1 converges only for dt <= 0.01) and
# with step halving from dt = 0.1.
fig-g73-hex: $(PROG)
	@mkdir -p out
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
fig-g73-wall: $(PROG)
	@mkdir -p out
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

figures:
	@$(MAKE) --no-print-directory deps deps-plot
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory fig1
	@$(MAKE) --no-print-directory fig-g72-ex1 fig-g72-ex1-ensemble \
	    fig-g72-ex2 fig-g72-large fig-g73-hex fig-g73-wall
	@echo "figures are in out/"

# ---------------------------------------------------------------- tests
build-tests: $(PROG) $(RUNNER)

test-run: build-tests
	BALLFILM_BIN=$(abspath $(PROG)) BALLFILM_ROOT=$(CURDIR) \
	  CK_DEFAULT_TIMEOUT=600 $(RUNNER)

test:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory test-run

check:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory BUILD=build/asan BINDIR=build/asan/bin \
	  SANITIZE="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" \
	  build-tests
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	BALLFILM_BIN=$(CURDIR)/build/asan/bin/ballfilm BALLFILM_ROOT=$(CURDIR) \
	BALLFILM_SANITIZED=1 CK_DEFAULT_TIMEOUT=3000 build/asan/tests/runner

# ---------------------------------------------------------------- bench
bench:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory all $(BENCH_BIN)
	@for b in $(BENCH_BIN); do echo "== $$b"; \
	  BALLFILM_ROOT=$(CURDIR) $$b || exit 1; done

clean:
	rm -rf build bin
