# rkforge: the commands a user types. Everything else lives in CMake, ctest and studies/.
#   make deps   install exactly the missing Debian packages (quiet, idempotent)
#   make build  configure and build (Release) into build/
#   make demo   Taylor bar from CAD to VTK on 2 ranks, printing where the results are
#   make test   build and run the whole test suite (ctest), then the sanitizer run (test-asan)
#   make fuzz   libFuzzer on the scene parser and the subdomain reader (FUZZ_SECONDS each)
#   make chain  a forging chain: hot upsetting, 5 s in air, a second blow (geometry/upsetting/chain.mk)
#   make bench  strong scaling of a >= 100k-particle Taylor bar on 1 and 2 ranks (BENCH_ARGS=...)
SHELL := /bin/bash
MAKEFLAGS += --no-print-directory
BUILD ?= build
JOBS  ?= $(shell nproc)
RANKS ?= 2
DEMO  ?= $(BUILD)/demo/taylor_bar

DEB_PACKAGES := build-essential cmake pkg-config libmetis-dev libsuitesparse-dev libeigen3-dev \
  libopenmpi-dev openmpi-bin libgmsh-dev libcgal-dev libhdf5-dev hdf5-tools libyaml-cpp-dev \
  nlohmann-json3-dev libcli11-dev libgtest-dev python3-meshio python3-numpy python3-matplotlib python3-yaml \
  python3-h5py python3-paraview xvfb xauth zlib1g-dev

export OMPI_ALLOW_RUN_AS_ROOT := 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM := 1
export OMPI_MCA_rmaps_base_oversubscribe := 1

.PHONY: deps build demo test test-asan chain bench fuzz clean
deps:
	@missing=$$(for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "rkforge: installing missing packages:" $$missing; \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing >/dev/null; \
	fi

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@scripts/demo.sh $(BUILD) $(DEMO) $(RANKS)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS)
	@$(MAKE) test-asan

# AddressSanitizer + UndefinedBehaviorSanitizer build (CMake preset "asan"): unit tests and small
# pipelines (ctest label asan). Leak reports are off: Open MPI and HDF5 keep global allocations.
# UBSan without its null and alignment checks: a quarter of its build time, and what they catch is caught
# otherwise here (docs/decisions.md).
# Built at -O1 -g1 (line tables for the reports): half the build time of -O2 -g, the run as fast.
test-asan: deps
	@cmake --preset asan >/dev/null
	@cmake --build build-asan -j $(JOBS) > build-asan/build.log 2>&1 || (tail -40 build-asan/build.log; exit 1)
	@cd build-asan && ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) -L asan

chain: build
	@$(MAKE) -f geometry/upsetting/chain.mk BIN=$(BUILD)/bin OUT=$(BUILD)/chain RANKS=$(RANKS)

bench: build
	@/usr/bin/python3 scripts/bench.py --bin $(BUILD)/bin --work $(BUILD)/bench $(BENCH_ARGS)

FUZZ_SECONDS ?= 60
# Leak detection is off: libhdf5 leaks small blocks on the error paths of corrupt files (not ours).
fuzz: deps
	@cmake --preset fuzz >/dev/null && cmake --build build-fuzz -j $(JOBS)
	@for t in scene subdomain; do \
	  echo "== fuzz_$$t for $(FUZZ_SECONDS) s (corpus tests/fuzz/corpus/$$t, findings in build-fuzz/findings/$$t)"; \
	  mkdir -p build-fuzz/corpus/$$t build-fuzz/findings/$$t; \
	  set -o pipefail; ASAN_OPTIONS=detect_leaks=0 build-fuzz/bin/fuzz_$$t build-fuzz/corpus/$$t tests/fuzz/corpus/$$t -max_total_time=$(FUZZ_SECONDS) \
	    -artifact_prefix=build-fuzz/findings/$$t/ -print_final_stats=1 2>&1 | tail -4 || exit 1; \
	done

clean:
	rm -rf $(BUILD)
