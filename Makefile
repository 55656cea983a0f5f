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
           $(shell pkg-config --libs gsl 2>/dev/null) -lm
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
        build-tests fig1 fig5 kink-dx2 film-orders fig6 fig8 fig9 multirate

all: $(PROG)

$(BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@

$(BUILD)/obj/tests/%.o: tests/%.c $(BUILD)/tests/suites.inc
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) -I$(BUILD)/tests $(CHECK_CFLAGS) $(CFLAGS) -c $< -o $@

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

# Yasuda Fig. 5: the perturbed kink, 1000 s at dt = 1e-3 s (10^6 steps),
# and the space-time picture of psi.
fig5: $(PROG)
	@mkdir -p out
	$(PROG) run runs/kink_steady.ini -q -o out/kink_steady.h5
	$(PY) plots/fig5_kink.py out/kink_steady.h5 -o out/fig5_kink.png
	$(PY) plots/film_spacetime.py out/kink_steady.h5 -o out/film_spacetime.png

# The kink's steady-state error for dx = 0.1, 0.05, 0.025 (falls as dx^2).
kink-dx2: $(PROG)
	@mkdir -p out
	@for dx in 0.1 0.05 0.025; do \
	  $(PROG) run runs/kink_converge.ini -q -o out/kink_dx$$dx.h5 \
	      --set film.dx=$$dx | sed -n "s/^film: kink error/dx = $$dx: kink error/p"; \
	done

# Yasuda Fig. 6: balls in the static kink potential (A: dt = 1e-4 s, B:
# 8e-4 s, C: peaks for 1e-4, 5.5e-4, 8e-4 s with an ensemble of shifted
# starts, D: one ball, 500 s).
KINK_ENS := 1e-12 1e-10 1e-8 1e-6 -1e-8
fig6: $(PROG)
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
fig8: $(PROG)
	@mkdir -p out
	$(PROG) run runs/coupled_fig8.ini -q -o out/coupled_fig8.h5
	$(PY) plots/fig8_coupled.py out/coupled_fig8.h5 -o out/fig8_coupled.png

fig9: $(PROG)
	@mkdir -p out
	$(PROG) run runs/coupled_fig9.ini -q -o out/coupled_fig9.h5
	$(PY) plots/fig8_coupled.py out/coupled_fig9.h5 -o out/fig9_coupled.png

# Multirate option against the single-rate run (Fig. 8 scene, 0-1 s).
MR_K := 3 10 30 100 300
multirate: $(PROG)
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

# Observed orders of the film scheme in dx and in dt (README).
film-orders: $(BUILD)/bench/film_orders
	$(BUILD)/bench/film_orders

figures:
	@$(MAKE) --no-print-directory deps deps-plot
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory fig1
	@$(MAKE) --no-print-directory fig5
	@$(MAKE) --no-print-directory kink-dx2
	@$(MAKE) --no-print-directory fig6
	@$(MAKE) --no-print-directory multirate
	@$(MAKE) --no-print-directory fig8
	@$(MAKE) --no-print-directory fig9
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
	@for b in $(BENCH_BIN); do echo "== $$b"; $$b || exit 1; done

clean:
	rm -rf build bin
