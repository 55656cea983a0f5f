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
        build-tests fig1 fig2 fig3 fig4 converge-figures

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

# Yasuda Fig. 2: first-return maps, lower ball 1.2 g (A) and 0.8 g (B),
# MV2M for 1000 s with the Lyapunov estimate; first at the paper's
# dt = 1e-4 s, then at 1e-5 s (see README for why both).  About 1 min.
FIG2_SET := --set lyapunov.enabled=yes
fig2: $(PROG)
	@mkdir -p out
	$(PROG) run runs/two_balls_A.ini -q -o out/fig2_A.h5 $(FIG2_SET)
	$(PROG) run runs/two_balls_B.ini -q -o out/fig2_B.h5 $(FIG2_SET)
	$(PROG) run runs/two_balls_A.ini -q -o out/fig2_A_dt1e-5.h5 $(FIG2_SET) \
	    --set scene.dt=1e-5 --set scene.output_every=1000
	$(PROG) run runs/two_balls_B.ini -q -o out/fig2_B_dt1e-5.h5 $(FIG2_SET) \
	    --set scene.dt=1e-5 --set scene.output_every=1000
	$(PY) plots/fig2_return_map.py out/fig2_A.h5 out/fig2_B.h5 \
	    out/fig2_A_dt1e-5.h5 out/fig2_B_dt1e-5.h5 -o out/fig2_return_map.png

# Yasuda Fig. 3: lower ball 0.8 g with (A) Verlet 1e-4 s, (B) Verlet 1e-5 s,
# (C) RK4, (D) RK3, (E) implicit mid-point at 1e-4 s, 1000 s each.  RK3
# loses about 40% of the energy over the run; its energy bound is lifted
# so that the figure shows all of it.  About 1 min.
fig3: $(PROG)
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

# Yasuda Fig. 4: over 500-501 s, every step.  Each run stops at t = 500 s
# (--stop-after writes a checkpoint, exit 6) and continues with a row per
# step ([scene] output_every = 1) to 501 s.  The MV2M run also records the
# one-step difference Verlet - second-order mid-point ([compare]).
FIG4_SET := --set scene.t_end=501 --set compare.a=verlet
fig4: $(PROG)
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
# integrator issue): the harmonic oscillator and the bouncing ball.
converge-figures: $(PROG)
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

figures:
	@$(MAKE) --no-print-directory deps deps-plot
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory fig1
	@$(MAKE) --no-print-directory fig2
	@$(MAKE) --no-print-directory fig3
	@$(MAKE) --no-print-directory fig4
	@$(MAKE) --no-print-directory converge-figures
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
