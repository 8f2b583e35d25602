#!/usr/bin/env bash
# Penumbra set-up for a fresh Debian 12 machine: installs every dependency from Debian's
# packages and client/'s npm packages (npm ci), then configures and builds Release into build/.
#
#   scripts/setup.sh            install + build
#   scripts/setup.sh --deps     install only
#   scripts/setup.sh --build    build only (dependencies already installed)
#
# Environment: BUILD_DIR (default build), BUILD_TYPE (default Release), JOBS (default nproc).
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
    g++ cmake make pkg-config git ca-certificates
    libcgal-dev libgmp-dev libmpfr-dev
    libopenmesh-dev
    libembree-dev
    libvtk9-dev
    libopenexr-dev
    libtbb-dev
    libeigen3-dev
    libassimp-dev
    nlohmann-json3-dev
    libcli11-dev
    libcpp-httplib-dev
    libspdlog-dev libfmt-dev
    libpng-dev
    libstb-dev
    libtinygltf-dev
    nodejs
    libnanoflann-dev
    libgtest-dev libgmock-dev
    libbenchmark-dev
    xvfb xauth
    chromium
    clang-format
)

need_install() {
    local p
    for p in "${PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || return 0
    done
    return 1
}

install_deps() {
    if ! need_install; then
        echo "setup: all Debian packages already installed"
        return
    fi
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    echo "setup: installing ${#PACKAGES[@]} Debian packages (about 2 minutes on a bare machine)"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
        "${PACKAGES[@]}" >/dev/null
}

# client/'s npm packages (the glTF validator, three.js, and playwright-core + pngjs for the
# browser test, which drives Debian's chromium), pinned by client/package-lock.json. Debian's
# nodejs comes without npm (its own package); NodeSource's nodejs carries it.
install_npm_packages() {
    if ! command -v npm >/dev/null; then
        local sudo=""
        [ "$(id -u)" -eq 0 ] || sudo="sudo"
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends npm \
            >/dev/null
    fi
    (cd client && npm ci --no-audit --no-fund)
}

build() {
    local dir="${BUILD_DIR:-build}"
    local jobs="${JOBS:-$(nproc)}"
    cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" -DPENUMBRA_WERROR=ON
    cmake --build "$dir" -j "$jobs"
}

case "${1:-all}" in
    --deps) install_deps; install_npm_packages ;;
    --build) build ;;
    all) install_deps; install_npm_packages; build ;;
    *) echo "usage: scripts/setup.sh [--deps|--build]" >&2; exit 2 ;;
esac
