# rkforge: the commands a user types. Everything else lives in CMake, ctest and studies/.
#   make deps   install exactly the missing Debian packages (quiet, idempotent)
#   make build  configure and build (Release) into build/
#   make demo   Taylor bar from CAD to VTK on 2 ranks, printing where the results are
#   make test   build and run the whole test suite (ctest)
#   make bench  strong scaling of a >= 100k-particle Taylor bar on 1 and 2 ranks (BENCH_ARGS=...)
SHELL := /bin/bash
MAKEFLAGS += --no-print-directory
BUILD ?= build
JOBS  ?= $(shell nproc)
RANKS ?= 2
DEMO  ?= $(BUILD)/demo/taylor_bar

DEB_PACKAGES := build-essential cmake pkg-config libmetis-dev libsuitesparse-dev libeigen3-dev \
  libopenmpi-dev openmpi-bin libgmsh-dev libcgal-dev libhdf5-dev hdf5-tools libyaml-cpp-dev \
  nlohmann-json3-dev libcli11-dev libgtest-dev python3-meshio python3-numpy python3-matplotlib

export OMPI_ALLOW_RUN_AS_ROOT := 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM := 1
export OMPI_MCA_rmaps_base_oversubscribe := 1

.PHONY: deps build demo test bench clean
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

bench: build
	@/usr/bin/python3 scripts/bench.py --bin $(BUILD)/bin --work $(BUILD)/bench $(BENCH_ARGS)

clean:
	rm -rf $(BUILD)
