# Flexible multibody FE reproduction suite: the two commands are `make all` and `make test`.
#
#   make all      install missing Debian packages, build, run every study, draw every figure, write the report
#   make test     install missing packages, build, run every unit test and every study's checks (CTest)
#   make deps     install the missing Debian packages (as root; otherwise print the apt-get line)
#   make <study>  run one study and draw its figures (cfl_tables, portal_frame_modes, ...)
#   make report   rebuild figures/REPORT.md and figures/REPORT.html from build/results
#   make bench    the performance benchmarks
#   make fuzz     libFuzzer targets for the Gmsh reader, the case-file readers and the deck reader (build-fuzz/, clang)
#   make sanitize unit tests and the short studies under ASan + UBSan (build-sanitize/)
#   make clean    remove build/ (and build-fuzz/, build-sanitize/)
BUILD   ?= build
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release
# OpenMP threads sleep instead of spinning while they wait: ctest -j runs several programs at once,
# and spinning threads then steal each other's cores (measured: 2-thread explicit runs 3x slower than
# one thread on a busy 2-core machine with the default policy, no loss with passive). Set it in the
# environment to override.
export OMP_WAIT_POLICY ?= passive

# Every Debian package the project needs, build tools included (clang and its runtime for `make fuzz`;
# chromium: headless screenshots of figures/REPORT.html, to look at the report as a reader sees it).
DEB_PACKAGES := cmake make g++ pkg-config \
  libeigen3-dev libspectra-dev libgsl-dev libhdf5-dev hdf5-tools \
  nlohmann-json3-dev libtomlplusplus-dev libfmt-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  gnuplot-nox gmsh libgmsh-dev calculix-ccx \
  libsuitesparse-dev libopenblas0-serial \
  libopenmpi-dev openmpi-bin \
  clang libclang-rt-14-dev lld ninja-build chromium ccache \
  python3-meshio python3-h5py

empty :=
space := $(empty) $(empty)

STUDIES := $(sort $(notdir $(patsubst %/,%,$(dir $(wildcard studies/*/CMakeLists.txt)))))

.PHONY: all test deps build configure report bench fuzz sanitize clean studies $(STUDIES) $(addprefix full-,$(STUDIES))

# Runs every study even when one fails (-k), writes the report, then reports failure if any study failed.
# The studies run JOBS at a time, the longest first (FULL_FIRST): chicken_shackling's --full is ~70 % of
# the CPU time and leaves part of a core idle between its runs, which the other studies fill. One after
# another the cores stood ~34 % idle (1 h 30 min 34 s); two at a time 1 h 18 min 50 s, 96 % busy
# (PERFORMANCE.md). Every study writes its own results and figures, so running two at once changes no
# file (CTest runs them side by side too). Each study's output is printed whole when it ends
# (--output-sync), not interleaved with the other's.
FULL_FIRST := chicken_shackling football_sweep finger_damping
FULL_ORDER := $(foreach s,$(FULL_FIRST),$(filter $(s),$(STUDIES))) $(filter-out $(FULL_FIRST),$(STUDIES))
# (The sub-make has its own recipe line: `make -n all` runs a line naming $(MAKE), so nothing else may share it.)
all: deps build
	@echo "== the $(words $(STUDIES)) studies --full, $(JOBS) at a time, the longest first: each study's output is printed when it ends;"; \
	echo "   meanwhile: tail -f $(BUILD)/logs/<study>.log"
	@$(MAKE) --no-print-directory -k -j $(JOBS) --output-sync=target $(addprefix full-,$(FULL_ORDER)); echo $$? > $(BUILD)/.studies-status
	@status=$$(cat $(BUILD)/.studies-status 2>/dev/null || echo 1); \
	$(BUILD)/bin/fem-report --reference reference --results $(BUILD)/results --figures figures; \
	$(REPORT_PAGE) || status=1; \
	exit $$status

# One study's whole run (--full) for `make all`: its output goes to $(BUILD)/logs/<study>.log as it runs
# and is printed whole at its end, with when it started and how long it took.
$(addprefix full-,$(STUDIES)): full-%:
	@mkdir -p $(BUILD)/logs; echo "== $* --full (started $$(date -u +%H:%M:%S))"; start=$$(date +%s); \
	$(BUILD)/bin/$* --figures figures --full > $(BUILD)/logs/$*.log 2>&1; status=$$?; \
	cat $(BUILD)/logs/$*.log; \
	echo "== $* --full: exit $$status after $$(( $$(date +%s) - start )) s"; exit $$status

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

# ccache (when installed: make deps installs it) keeps compiled objects across build folders and
# clean clones on this machine, so a rebuild after `make clean` or in a fresh clone recompiles only
# what changed. Paths below the project are hashed relative to it (a clone elsewhere hits the same cache).
export CCACHE_BASEDIR ?= $(CURDIR)
# Depend mode: on a miss ccache reads the compiler's own dependency file instead of running the
# preprocessor a second time, which a cold build (CI's clean clone on a new machine) pays on every
# unit (cold builds of main: 1,416 s of CPU through ccache's preprocessor mode, 1,301 s without ccache).
export CCACHE_DEPEND ?= 1
CCACHE_LAUNCHER := $(if $(shell command -v ccache 2>/dev/null),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

# Configure once; the stamp is written only when CMake succeeded, so a configure that failed (say,
# `make <study>` before the packages were installed) is simply run again by the next make instead of
# leaving a half-made build folder that every later make trips over. CMake retries whatever it did
# not find. tests/makefile/configure_recovers.sh checks this in a scratch copy.
# A new build folder is generated for Ninja (Debian ninja-build, make deps), which compiles a target's
# sources while the libraries it links are still being built (CMake's Makefiles wait for them); a folder
# that already exists keeps the generator it was made with (CMake refuses to switch).
GENERATOR := $(if $(wildcard $(BUILD)/CMakeCache.txt),,$(if $(shell command -v ninja 2>/dev/null),-G Ninja))
$(BUILD)/.configured:
	cmake -S . -B $(BUILD) $(GENERATOR) $(CMAKE_FLAGS) $(CCACHE_LAUNCHER)
	@touch $@

configure: $(BUILD)/.configured

build: configure
	cmake --build $(BUILD) -j $(JOBS)

studies: $(STUDIES)

# One study: run it (its exit status is its checks), draw its figures into figures/.
$(STUDIES): build
	$(BUILD)/bin/$@ --figures figures

report: build
	$(BUILD)/bin/fem-report --reference reference --results $(BUILD)/results --figures figures
	$(REPORT_PAGE)

# The report page opened in headless Chromium: images, links, counts and filters checked, screenshots
# figures/REPORT-desktop.png and REPORT-narrow.png saved (tests/report/check_report_page.py).
REPORT_PAGE = python3 tests/report/check_report_page.py page figures/REPORT.html figures

bench: build
	cmake --build $(BUILD) --target benchmarks -j $(JOBS)
	@set -e; for b in $(BUILD)/bench/*; do [ -x "$$b" ] && echo "== $$b" && "$$b"; done; true

# Sanitizer runtime settings shared by `make fuzz` and `make sanitize`: stop at the first report;
# libgmsh's own leaks are suppressed by library (tests/sanitize/lsan.supp), ours are not.
ASAN_FLAGS := detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=0
LSAN_FLAGS := suppressions=$(CURDIR)/tests/sanitize/lsan.supp:print_suppressions=0
UBSAN_FLAGS := print_stacktrace=1:halt_on_error=1
SANITIZER_ENV := ASAN_OPTIONS=$(ASAN_FLAGS) LSAN_OPTIONS=$(LSAN_FLAGS) UBSAN_OPTIONS=$(UBSAN_FLAGS)
# While fuzzing, reports are not symbolized: read_gmsh's reader process (a fork of the fuzz target,
# its stderr sent to /dev/null) spent 0.3-0.5 s symbolizing each AddressSanitizer report of libgmsh
# asking for 2^51 bytes before it aborted, which cost fuzz_gmsh a third of its time and, past its
# 0.25 s read limit, turned the crash into a reported time-out. A finding is replayed symbolized below.
FUZZ_ENV := ASAN_OPTIONS=$(ASAN_FLAGS):symbolize=0 LSAN_OPTIONS=$(LSAN_FLAGS) UBSAN_OPTIONS=$(UBSAN_FLAGS):symbolize=0

# Fuzzing: clang's libFuzzer with ASan and UBSan in $(FUZZ_BUILD); each target runs FUZZ_RUNS
# executions starting from its seed corpus tests/fuzz/corpus/<target> (kept in the repository; new
# inputs it finds go to $(FUZZ_BUILD)/corpus/<target>). Crashes are written to $(FUZZ_BUILD)/.
FUZZ_BUILD   ?= build-fuzz
FUZZ_RUNS    ?= 100000
FUZZ_TARGETS := gmsh modal_case topopt_case explicit_case deck
fuzz: deps
	@[ -f $(FUZZ_BUILD)/.configured ] || { cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DFEM_FUZZ=ON $(CCACHE_LAUNCHER) && touch $(FUZZ_BUILD)/.configured; }
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	@set -e; for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_BUILD)/corpus/$$t; echo "== fuzz_$$t: $(FUZZ_RUNS) executions"; \
	  $(FUZZ_ENV) $(FUZZ_BUILD)/tests/fuzz/fuzz_$$t -runs=$(FUZZ_RUNS) -timeout=20 -rss_limit_mb=4096 \
	    -max_len=8192 -print_final_stats=1 -artifact_prefix=$(FUZZ_BUILD)/crash-$$t- \
	    $(FUZZ_BUILD)/corpus/$$t tests/fuzz/corpus/$$t > $(FUZZ_BUILD)/fuzz_$$t.log 2>&1 \
	    || { tail -40 $(FUZZ_BUILD)/fuzz_$$t.log; a=$$(ls -t $(FUZZ_BUILD)/crash-$$t-* 2>/dev/null | head -1); \
	         [ -z "$$a" ] || { echo "== $$a replayed with symbolized reports:"; \
	           $(SANITIZER_ENV) $(FUZZ_BUILD)/tests/fuzz/fuzz_$$t $$a 2>&1 | tail -60; }; exit 1; }; \
	  grep -E "^Done|stat::number_of_executed_units|stat::peak_rss_mb" $(FUZZ_BUILD)/fuzz_$$t.log; \
	done

# Sanitizers: everything built with ASan + UBSan in $(SANITIZE_BUILD); runs the unit tests and the
# short studies (the long ones, minutes each in a normal build, take 3-10x longer instrumented).
# Neither the benchmarks (CMakeLists.txt) nor the MPI programs are built there: neither is run.
SANITIZE_BUILD   ?= build-sanitize
SANITIZE_STUDIES ?= cfl_tables portal_frame_modes finger_twist topology_cases
sanitize: deps
	@[ -f $(SANITIZE_BUILD)/.configured ] || { cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DFEM_SANITIZE=ON -DFEM_MPI=OFF $(CCACHE_LAUNCHER) && touch $(SANITIZE_BUILD)/.configured; }
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && $(SANITIZER_ENV) ctest --output-on-failure -j $(JOBS) -L unit
	cd $(SANITIZE_BUILD) && $(SANITIZER_ENV) ctest --output-on-failure -j $(JOBS) \
	  -R '^($(subst $(space),|,$(strip $(SANITIZE_STUDIES))))$$'

clean:
	rm -rf $(BUILD) $(FUZZ_BUILD) $(SANITIZE_BUILD)
