# Two commands on a fresh Debian 12 machine: `make demo` and `make test`.
# Both install the Debian packages the build needs (apt-get, as root or through sudo),
# configure a Release build in build/ and build it.

BUILD ?= build
JOBS ?= $(shell nproc)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
DEBIAN_PACKAGES := cmake g++ make libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev \
                   libbenchmark-dev libopenmesh-dev libtinyobjloader-dev libosd-dev libtbb-dev \
                   libembree-dev libstb-dev libturbojpeg0-dev lib3mf-dev libzip-dev libcgal-dev libtinygltf-dev \
                   clang-16 libclang-rt-16-dev
# cpp-httplib: the studio's server (`meander serve`); meshoptimizer: its compressed views.
DEBIAN_PACKAGES += libcpp-httplib-dev libmeshoptimizer-dev
# The Python package (python/, for Debian's /usr/bin/python3) and its tests.
DEBIAN_PACKAGES += pybind11-dev python3-dev python3-numpy python3-pytest
# rsvg-convert: the tests rasterise `meander image`'s SVG with a renderer that is not ours;
# inkscape: they check that Inkscape reads a drawing's layers and paths.
DEBIAN_PACKAGES += librsvg2-bin inkscape

.PHONY: deps build install-python blender-addon demo test studio browser blender slicer validator bench gallery clean sanitize-config test-sanitize fuzz fuzz-corpus fuzz-check

deps:
	@missing=$$(for p in $(DEBIAN_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing Debian packages:" $$missing; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi

# The benchmarks are built by `make bench` only (BENCH=ON), not for the tests.
BENCH ?= OFF
build: deps studio
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DMEANDER_BUILD_BENCH=$(BENCH) > /dev/null
	cmake --build $(BUILD) -j $(JOBS)

# The Python package (docs/python.md) into Debian's Python's site packages, where
# /usr/bin/python3 imports it.
PYTHON_SITE ?= $(shell /usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_path("platlib"))')
install-python: build
	$(SUDO) mkdir -p $(PYTHON_SITE)
	$(SUDO) rm -rf $(PYTHON_SITE)/meander
	$(SUDO) cp -r $(BUILD)/python/meander $(PYTHON_SITE)/meander
	@echo "install-python: meander is in $(PYTHON_SITE)"

# The Blender add-on with the compiled module inside (docs/blender.md): install the zip in
# Blender (Edit > Preferences > Add-ons > Install).
blender-addon: build
	@echo "blender-addon: $(BUILD)/meander-blender.zip"

demo: build
	@mkdir -p out
	./$(BUILD)/meander generate pretzel --faces 6400 -o out/pretzel.obj
	./$(BUILD)/meander curve out/pretzel.obj -o out/pretzel_curve.obj --triangles out/pretzel_cycle.obj --png out/pretzel.png --verbose
	./$(BUILD)/meander curve out/pretzel.obj -o out/pretzel_curve.svg
	./$(BUILD)/meander wire out/pretzel.obj -o out/pretzel_wire.stl --samples 2 --report out/pretzel_wire.json --png out/pretzel_wire.png --size 800x600
	./$(BUILD)/meander wire out/pretzel.obj -o out/pretzel_wire_100mm.stl --model-size 100mm --spacing 3mm --report out/pretzel_wire_100mm.json --png out/pretzel_wire_100mm.png --size 800x600
	@grep -q '"printable": true' out/pretzel_wire_100mm.json && echo "demo: out/pretzel_wire_100mm.stl is a wire of the pretzel 100 mm long, its passes 3 mm apart: printable with a 0.4 mm nozzle (out/pretzel_wire_100mm.json)"
	@echo "demo: outputs are in out/"

# The suite in the Release build, the same suite again under the sanitizers (which also
# builds the fuzz targets), then each fuzz target's seeds and a fixed number of inputs more.
# Each phase's start is printed (UTC), so that a run's log shows where its time went.
test: build validator browser blender slicer
	@echo "make test: $$(date -u +%T) the Release suite"
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
	@echo "make test: $$(date -u +%T) the sanitized build and suite"
	$(MAKE) test-sanitize
	@echo "make test: $$(date -u +%T) the fuzz targets on their seeds"
	$(MAKE) fuzz-check
	@echo "make test: $$(date -u +%T) done"

# The Khronos glTF validator (npm) checks the GLB files Meander writes.
validator:
	@if ! command -v npm > /dev/null; then \
	  echo "make test: installing Debian's nodejs and npm for the glTF validator"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq nodejs npm; \
	fi
	cd tests && npm ci --no-audit --no-fund --loglevel=error

# The hardening build (docs/robustness.md): clang with AddressSanitizer, UndefinedBehaviorSanitizer
# and libFuzzer's coverage, for the whole suite (`make test-sanitize`) and the fuzz targets
# (`make fuzz`, each run FUZZ_SECONDS, one after the other). Clang 16, not Debian 12's
# default 14: the library captures structured bindings in lambdas (C++20), which clang
# accepts from 16 on.
SANITIZE_BUILD ?= build-sanitize
FUZZ_SECONDS ?= 60
# `make test` (fuzz-check) runs every seed of each fuzz target (tests/corpus,
# tests/regressions, the small shared meshes) under the sanitizers, then this many inputs
# more from a fixed seed: a count, not a time, so that a busy machine runs the same ones
# (3000: the seeds are the regression check; new inputs are `make fuzz`'s work, and the
# suite must stay within 25 minutes from a fresh clone).
FUZZ_RUNS ?= 3000
# Which tests test-sanitize runs (a ctest -R regex; empty: all of them).
SANITIZE_TESTS ?=

# -O1 and line tables only (enough for the sanitizers' stack traces) build in less than
# half the time of RelWithDebInfo's -O2 -g: the build is most of what the sanitizer suite
# adds to CI.
sanitize-config: deps
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-16 \
	  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only -DNDEBUG" -DMEANDER_BUILD_FUZZ=ON > /dev/null

# The sanitized run leaves out the tests that repeat a whole pipeline on each large real
# mesh or scan (a third of its time, measured: 323 of 904 s), the browser test (140 s
# sanitized, with the spacing slider's relaxed curves) and the CLI's repeats of --spacing,
# --model-size and --branches on generated shapes (110 s): the Release run checks them,
# and the same code runs under the sanitizers in the library's own tests (Relax, Remesh,
# Cycle, Printability, the studio's server), on the small real meshes of the other tests
# and on the corpora. It also leaves out the studio's every-mode-and-quadrangulation
# repeat (ResultSizeIsKnownBeforeAnyWork, 11 s), the 250 MB streamed curve (14 s; the
# writer's buffer edges run sanitized in AtomicFile.LargeCurveReadsBackExactly) and the
# CLI's line pictures (CliImage, 12 s; tone_mesh runs sanitized in ToneMesh), and the
# corpus files' expected outcomes (Corpus/, 47 s), which fuzz-check replays under the
# sanitizers as its seeds anyway. Of the prints (250 s sanitized, measured) it leaves out
# the shell and its clearance on genus 3 (and the clearance on genus 2 and on Spot), the
# 1,600-face pretzel's 800 bridges, the bridged wires on five shapes (35 s) and the
# bridged variable wires, the studio's bridged wires and two-colour print, and the
# kitten's sampled shell (34 s sanitized; it passed sanitized when it was added, at
# 7dc4612): the sphere, torus, genus 2 and disc take the same shell and clearance code,
# and the constant wire's CLI test and same-bytes test the same union and plan, sanitized.
# SANITIZE_SKIP= runs everything.
SANITIZE_SKIP ?= Index/CurveOnRealMesh|RealMeshes/|VariableWireAtDefaultLevelsOnCoarseMeshes|VariableWireOnAScan|DenseRibbonsDoNotSelfIntersect|AgreesWithCgalOnRealMeshes|studio_e2e|Spacing.TheGapsAre|Spacing.AFinerSpacing|CliModelSize|BranchesSetTheLeavesThatVerbosePrints|ResultSizeIsKnownBeforeAnyWork|LargeFileReadsBackAsTheCurve|CliImage|Corpus/|AClearanceDrawsTheTwoSolidsApart/genus|TwoSolidsThatMakeTheShell/genus_3|AClearanceMakesTwoPiecesToPrintApart|ManyBridgesStayClearOnceRoundedToFloats|MakeTheWireOneRigidSolid|BridgesComeWithTheFullWires|MakeTheVariableWireOneRigidSolid|TheVariableWireFromTheCliIsOnePiece|ADuotoneWithAShellIsATwoColourPrint|AThinScanIsSampledIntoTheSameTwoColourPrintEveryRun|AScanTooThinForAWallThatFollowsTheQuadsIsSampled|AThinScanIsSampledIntoTwoPiecesToPrintApart|QuadsTooSmallForTheGapAreSampled
test-sanitize: sanitize-config validator
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp ctest --output-on-failure -j $(JOBS) \
	  $(if $(SANITIZE_TESTS),-R '$(SANITIZE_TESTS)') $(if $(SANITIZE_SKIP),-E '$(SANITIZE_SKIP)')

fuzz: sanitize-config
	cmake --build $(SANITIZE_BUILD) -j $(JOBS) --target fuzzers
	fuzz/run.sh $(SANITIZE_BUILD) $(FUZZ_SECONDS)

# Minimises what `make fuzz` found into fuzz/corpus/ (committed, replayed by make test).
fuzz-corpus: sanitize-config
	cmake --build $(SANITIZE_BUILD) -j $(JOBS) --target fuzzers
	fuzz/run.sh $(SANITIZE_BUILD) --merge

fuzz-check: sanitize-config
	cmake --build $(SANITIZE_BUILD) -j $(JOBS) --target fuzzers
	fuzz/run.sh $(SANITIZE_BUILD) --runs $(FUZZ_RUNS)

# The studio's page (studio/: three.js built by vite into studio/dist, which `meander serve`
# serves; no CDN at run time).
studio: studio/dist/index.html

# Rebuilt only when its sources change (npm ci takes seconds even when nothing did).
studio/dist/index.html: studio/package-lock.json studio/index.html studio/vite.config.js $(wildcard studio/src/*)
	@if ! command -v npm > /dev/null; then \
	  echo "make: installing Debian's nodejs and npm for the studio's page"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq nodejs npm; \
	fi
	cd studio && npm ci --no-audit --no-fund --loglevel=error && npm run --silent build > /dev/null

# Debian's Blender for the add-on's test (ctest blender, which skips with a message where it
# could not be installed, and fails under CI).
blender:
	@command -v blender > /dev/null || { echo "make test: installing Debian's blender for the add-on's test"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq blender \
	  || echo "make test: blender could not be installed: the add-on's test will be skipped (failed under CI)"; }

# Debian's PrusaSlicer: the tests open the two-colour prints with `prusa-slicer --info`
# (skipped with a message where it could not be installed, failed under CI).
slicer:
	@command -v prusa-slicer > /dev/null || { echo "make test: installing Debian's prusa-slicer for the two-colour prints' test"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends prusa-slicer \
	  || echo "make test: prusa-slicer could not be installed: its checks will be skipped (failed under CI)"; }

# Debian's chromium for the studio's browser test (ctest studio_e2e, which skips with a
# message where it could not be installed, and fails under CI).
browser:
	@command -v chromium > /dev/null || { echo "make test: installing Debian's chromium for the studio's browser test"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq chromium \
	  || echo "make test: chromium could not be installed: the studio's browser test will be skipped (failed under CI)"; }

bench:
	$(MAKE) build BENCH=ON
	bench/run.sh

gallery: build
	MEANDER=$(BUILD)/meander docs/make_gallery.sh
	MEANDER=$(CURDIR)/$(BUILD)/meander MESHES=$(CURDIR)/../shared/meshes docs/make_wire_figures.sh
	MEANDER=$(CURDIR)/$(BUILD)/meander MESHES=$(CURDIR)/../shared/meshes docs/make_duotone_figures.sh
	MEANDER=$(CURDIR)/$(BUILD)/meander docs/make_printing_figures.sh

clean:
	rm -rf $(BUILD) out
