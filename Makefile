# Two commands on a fresh Debian 12 machine: `make demo` and `make test`.
# Both install the Debian packages the build needs (apt-get, as root or through sudo),
# configure a Release build in build/ and build it.

BUILD ?= build
JOBS ?= $(shell nproc)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
DEBIAN_PACKAGES := cmake g++ make libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev \
                   libbenchmark-dev libopenmesh-dev libtinyobjloader-dev libosd-dev libtbb-dev \
                   libembree-dev libstb-dev lib3mf-dev libcgal-dev libtinygltf-dev
# cpp-httplib: the studio's server (`meander serve`).
DEBIAN_PACKAGES += libcpp-httplib-dev

.PHONY: deps build demo test studio browser bench gallery clean

deps:
	@missing=$$(for p in $(DEBIAN_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing Debian packages:" $$missing; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi

build: deps studio
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DMEANDER_BUILD_BENCH=ON > /dev/null
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p out
	./$(BUILD)/meander generate pretzel --faces 6400 -o out/pretzel.obj
	./$(BUILD)/meander curve out/pretzel.obj -o out/pretzel_curve.obj --triangles out/pretzel_cycle.obj --png out/pretzel.png --verbose
	./$(BUILD)/meander curve out/pretzel.obj -o out/pretzel_curve.svg
	./$(BUILD)/meander wire out/pretzel.obj -o out/pretzel_wire.stl --samples 2 --report out/pretzel_wire.json --png out/pretzel_wire.png --size 800x600
	@echo "demo: outputs are in out/"

test: build browser
	@# The Khronos glTF validator (npm) checks the GLB files Meander writes.
	@if ! command -v npm > /dev/null; then \
	  echo "make test: installing Debian's nodejs and npm for the glTF validator"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq nodejs npm; \
	fi
	cd tests && npm ci --no-audit --no-fund --loglevel=error
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The studio's page (studio/: three.js built by vite into studio/dist, which `meander serve`
# serves; no CDN at run time).
studio:
	@if ! command -v npm > /dev/null; then \
	  echo "make: installing Debian's nodejs and npm for the studio's page"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq nodejs npm; \
	fi
	cd studio && npm ci --no-audit --no-fund --loglevel=error && npm run --silent build > /dev/null

# Debian's chromium for the studio's browser test (ctest studio_e2e, which skips with a
# message only where it could not be installed).
browser:
	@command -v chromium > /dev/null || { echo "make test: installing Debian's chromium for the studio's browser test"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq chromium \
	  || echo "make test: chromium could not be installed: the studio's browser test will be skipped"; }

bench: build
	bench/run.sh

gallery: build
	MEANDER=$(BUILD)/meander docs/make_gallery.sh
	MEANDER=$(CURDIR)/$(BUILD)/meander MESHES=$(CURDIR)/../shared/meshes docs/make_wire_figures.sh
	MEANDER=$(CURDIR)/$(BUILD)/meander MESHES=$(CURDIR)/../shared/meshes docs/make_duotone_figures.sh

clean:
	rm -rf $(BUILD) out
