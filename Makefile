# Flexible multibody FE reproduction suite: the two commands are `make all` and `make test`.
#
#   make all      install missing Debian packages, build, run every study, draw every figure, write the report
#   make test     install missing packages, build, run every unit test and every study's checks (CTest)
#   make deps     install the missing Debian packages (as root; otherwise print the apt-get line)
#   make <study>  run one study and draw its figures (cfl_tables, portal_frame_modes, ...)
#   make report   rebuild figures/REPORT.md and figures/REPORT.html from build/results
#   make bench    the performance benchmarks
#   make clean    remove build/
BUILD   ?= build
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release
# OpenMP threads sleep instead of spinning while they wait: ctest -j runs several programs at once,
# and spinning threads then steal each other's cores (measured: 2-thread explicit runs 3x slower than
# one thread on a busy 2-core machine with the default policy, no loss with passive). Set it in the
# environment to override.
export OMP_WAIT_POLICY ?= passive

# Every Debian package the project needs, build tools included (chromium: headless screenshots of
# figures/REPORT.html, to look at the report as a reader sees it).
DEB_PACKAGES := cmake make g++ pkg-config \
  libeigen3-dev libspectra-dev libgsl-dev libhdf5-dev hdf5-tools \
  nlohmann-json3-dev libtomlplusplus-dev libfmt-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  gnuplot-nox gmsh libgmsh-dev calculix-ccx \
  libsuitesparse-dev libopenblas0-serial \
  chromium

STUDIES := $(sort $(notdir $(patsubst %/,%,$(dir $(wildcard studies/*/CMakeLists.txt)))))

.PHONY: all test deps build configure report bench clean studies $(STUDIES)

# Runs every study even when one fails, writes the report, then reports failure if any study failed.
all: deps build
	@status=0; for s in $(STUDIES); do echo "== $$s"; $(BUILD)/bin/$$s --figures figures --full || status=1; done; \
	$(BUILD)/bin/fem-report --reference reference --results $(BUILD)/results --figures figures; \
	exit $$status

test: deps build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

deps:
	@missing=""; \
	for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -z "$$missing" ]; then echo "deps: all Debian packages present"; \
	elif [ "$$(id -u)" = 0 ]; then \
	  echo "deps: installing$$missing"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	else \
	  echo "deps: missing Debian packages; run:"; echo "  sudo apt-get install -y$$missing"; exit 1; \
	fi

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

configure: $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

studies: $(STUDIES)

# One study: run it (its exit status is its checks), draw its figures into figures/.
$(STUDIES): build
	$(BUILD)/bin/$@ --figures figures

report: build
	$(BUILD)/bin/fem-report --reference reference --results $(BUILD)/results --figures figures

bench: build
	@set -e; for b in $(BUILD)/bench/*; do [ -x "$$b" ] && echo "== $$b" && "$$b"; done; true

clean:
	rm -rf $(BUILD)
