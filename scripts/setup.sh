#!/usr/bin/env bash
# One-shot, idempotent set-up of everything the project needs on a Debian 12/13 machine:
#   1. Debian packages (build tools for SWI-Prolog, run-time libraries for open3d);
#   2. SWI-Prolog >= 9.1.12: Debian's package where the release has it, otherwise Debian 13's
#      source built into .deps/swipl (the project owns it; nothing of the system is upgraded);
#   3. a Python virtual environment .venv with the project and its dependencies (with the
#      extras dev, for the tests, cluster, Ray, whose back end the tests run, and stonesoup, the
#      Stone Soup baselines the tests run), janus-swi
#      built against that SWI-Prolog and pointed at it at interpreter start-up.
# Run again, it checks each step with a stamp and finishes in seconds.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
deps="$here/.deps"
mkdir -p "$deps"
log() { printf '[setup] %s\n' "$*" >&2; }
SUDO=""
[ "$(id -u)" = 0 ] || SUDO="sudo"

min_swipl=90112   # 9.1.12, as major*10000 + minor*100 + patch

version_code() {  # "9.2.9" -> 90209
  local IFS=.; set -- $1; echo $(( $1 * 10000 + $2 * 100 + ${3%%[!0-9]*} ))
}

# ---------------------------------------------------------------- 1. Debian packages
apt_packages=(cmake ninja-build gcc g++ make pkg-config libgmp-dev zlib1g-dev libreadline-dev
              libncurses-dev libedit-dev libusb-1.0-0 libgomp1 dpkg-dev)
missing=()
for p in "${apt_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
apt_updated=0
if [ ${#missing[@]} -gt 0 ]; then
  log "installing Debian packages: ${missing[*]}"
  $SUDO apt-get update -qq && apt_updated=1
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# ---------------------------------------------------------------- 2. SWI-Prolog
swipl_prefix="$deps/swipl"
# The build records how it was made; a build from before profile-guided optimisation (no
# record) is made again, once.
swipl_build_record="$swipl_prefix/.build-type"
swipl_bin=""
if [ -x "$swipl_prefix/bin/swipl" ] && [ -f "$swipl_build_record" ]; then
  swipl_bin="$swipl_prefix/bin/swipl"
elif command -v swipl >/dev/null 2>&1 && \
     [ "$(readlink -f "$(command -v swipl)")" != "$(readlink -f "$swipl_prefix/bin/swipl")" ] && \
     [ "$(swipl -q -g 'current_prolog_flag(version,V),write(V),nl' -t halt 2>/dev/null || echo 0)" -ge $min_swipl ]; then
  swipl_bin="$(command -v swipl)"
else
  [ $apt_updated = 1 ] || { $SUDO apt-get update -qq; apt_updated=1; }
  candidate=$(apt-cache policy swi-prolog-nox 2>/dev/null | sed -n 's/^ *Candidate: *//p')
  if [ -n "$candidate" ] && [ "$candidate" != "(none)" ] && \
     [ "$(version_code "${candidate%%+*}")" -ge $min_swipl ]; then
    log "installing swi-prolog-nox $candidate from Debian"
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends swi-prolog-nox >/dev/null
    swipl_bin=/usr/bin/swipl
  else
    log "Debian's SWI-Prolog ($candidate) is older than 9.1.12: building Debian 13's source into $swipl_prefix"
    src_list=/etc/apt/sources.list.d/anchoring-trixie-src.sources
    if [ ! -f "$src_list" ]; then
      # Derive the entry from the machine's own main Debian source (same mirror and key).
      srcs=$(ls /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null || true)
      uri=$(cat $srcs 2>/dev/null | sed -n -E 's/^URIs: *//p; s/^deb +(\[[^]]*\] +)?([^ ]+) .*/\2/p' \
            | grep -m1 -E '/debian/?$' || true)
      key=$(cat $srcs 2>/dev/null | sed -n 's/^Signed-By: *//p' | head -1)
      [ -n "$uri" ] || { log "no Debian apt source found to derive a deb-src entry from"; exit 1; }
      {
        echo "Types: deb-src"; echo "URIs: $uri"; echo "Suites: trixie"; echo "Components: main"
        [ -n "$key" ] && echo "Signed-By: $key"
      } | $SUDO tee "$src_list" >/dev/null
      $SUDO apt-get update -qq
    fi
    work="$deps/swipl-src"
    mkdir -p "$work"
    tarball=$(ls "$work"/swi-prolog_*.orig.tar.* 2>/dev/null | head -1 || true)
    if [ -z "$tarball" ]; then
      (cd "$work" && apt-get source --download-only --tar-only swi-prolog >/dev/null 2>&1 || \
                     apt-get source --download-only swi-prolog >/dev/null)
      tarball=$(ls "$work"/swi-prolog_*.orig.tar.* | head -1)
    fi
    rm -rf "$work/src" && mkdir -p "$work/src"
    tar -xf "$tarball" -C "$work/src" --strip-components=1
    # PGO: SWI-Prolog's profile-guided build (an instrumented build runs its benchmark suite,
    # then the final build uses the profile); the filter steps about 5 % faster than with
    # Release (measured on the shell game's recorded filter frames, one and two threads).
    # Release if that build fails.
    build_swipl() {
      rm -rf "$work/build"
      cmake -S "$work/src" -B "$work/build" -G Ninja \
        -DCMAKE_INSTALL_PREFIX="$swipl_prefix" -DCMAKE_BUILD_TYPE="$1" \
        -DSWIPL_PACKAGES_X=OFF -DSWIPL_PACKAGES_JAVA=OFF -DSWIPL_PACKAGES_ODBC=OFF \
        -DSWIPL_PACKAGES_BDB=OFF -DSWIPL_PACKAGES_QT=OFF -DSWIPL_PACKAGES_ARCHIVE=OFF \
        -DSWIPL_PACKAGES_PCRE=OFF -DSWIPL_PACKAGES_YAML=OFF -DSWIPL_PACKAGES_SSL=OFF \
        -DSWIPL_PACKAGES_TIPC=OFF -DSWIPL_PACKAGES_PYTHON=ON \
        -DINSTALL_DOCUMENTATION=OFF -DBUILD_TESTING=OFF -DUSE_GMP=ON >"$work/cmake.log" 2>&1 \
        || { tail -30 "$work/cmake.log"; return 1; }
      ninja -C "$work/build" >"$work/build.log" 2>&1 || { tail -40 "$work/build.log"; return 1; }
      ninja -C "$work/build" install >"$work/install.log" 2>&1 || { tail -20 "$work/install.log"; return 1; }
    }
    if build_swipl PGO; then
      build_type=PGO
    else
      log "the profile-guided build of SWI-Prolog failed: building it as Release"
      build_swipl Release || exit 1
      build_type=Release
    fi
    echo "$build_type" > "$swipl_build_record"
    rm -rf "$work/src" "$work/build"
    swipl_bin="$swipl_prefix/bin/swipl"
  fi
fi
swipl_home=$("$swipl_bin" --dump-runtime-variables | sed -n 's/^PLBASE="\(.*\)";/\1/p')
log "SWI-Prolog: $swipl_bin (home $swipl_home)"

# ---------------------------------------------------------------- 2b. the column library
# The batched filter's columns in C (prolog/ddc/batch/c/ddc_columns.c, loaded by prolog/ddc/batch/ddc_batch_col.pl),
# compiled by the swipl-ld of that SWI-Prolog (Debian's swi-prolog-core ships it too), again
# when the source or the SWI-Prolog changes. Without it the engine runs its columns in Prolog.
columns_src="$here/prolog/ddc/batch/c/ddc_columns.c"
columns_so="$here/prolog/ddc/batch/c/ddc_columns.so"
columns_stamp="$here/prolog/ddc/batch/c/.ddc_columns.built"
columns_want="$(sha1sum < "$columns_src" | cut -c1-12) $swipl_bin"
if [ ! -f "$columns_so" ] || [ "$(cat "$columns_stamp" 2>/dev/null)" != "$columns_want" ]; then
  log "compiling the batched filter's column library ($columns_so)"
  swipl_ld="$(dirname "$swipl_bin")/swipl-ld"
  [ -x "$swipl_ld" ] || swipl_ld=$(command -v swipl-ld || true)
  [ -n "$swipl_ld" ] || { log "no swipl-ld next to $swipl_bin: cannot compile $columns_src"; exit 1; }
  rm -f "$columns_so"
  (cd "$here/prolog/ddc/batch/c" && PATH="$(dirname "$swipl_bin"):$PATH" \
     "$swipl_ld" -shared -cc-options,-O2,-Wall -o ddc_columns ddc_columns.c) \
    || { log "compiling $columns_src failed (above): the batched filter needs it for its speed"; exit 1; }
  "$swipl_bin" -q -g "use_module('$here/prolog/ddc/batch/ddc_batch_col'), col_backend(foreign)" -t halt \
    || { log "$columns_so was built but does not load in $swipl_bin"; exit 1; }
  echo "$columns_want" > "$columns_stamp"
fi

# ---------------------------------------------------------------- 3. Python environment
venv="$here/.venv"
py=${PYTHON:-python3.11}
command -v "$py" >/dev/null 2>&1 || py=python3
[ -x "$venv/bin/python" ] || { log "creating $venv"; "$py" -m venv "$venv"; }
stamp="$venv/.anchoring-installed"
want="$(cat pyproject.toml | sha1sum | cut -c1-12) $swipl_bin"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  log "installing the project and its Python dependencies"
  PATH="$(dirname "$swipl_bin"):$PATH" SWI_HOME_DIR="$swipl_home" \
    "$venv/bin/pip" install -q -e ".[app,dev,cluster,stonesoup]" 2>&1 | { grep -v "is ignored: it is neither" || true; }
  echo "$want" > "$stamp"
fi
# Packages whose metadata asks for opencv-python, which would overwrite the cv2 module of our
# opencv-python-headless: installed without dependencies (pyproject.toml lists those instead).
nodeps="python/probanchor/evaluation/requirements-nodeps.txt"
nodeps_stamp="$venv/.anchoring-nodeps"
if [ -f "$nodeps" ] && [ "$(sha1sum < "$nodeps")" != "$(cat "$nodeps_stamp" 2>/dev/null)" ]; then
  log "installing $nodeps without dependencies"
  "$venv/bin/pip" install -q --no-deps -r "$nodeps" 2>&1 | { grep -v "is ignored: it is neither" || true; }
  sha1sum < "$nodeps" > "$nodeps_stamp"
fi
# janus must find the SWI-Prolog it was built against, even with another swipl on PATH: set
# SWI_HOME_DIR (and PATH) at interpreter start-up through a .pth file, so that
# .venv/bin/python and every console command work without the user exporting anything.
site=$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
cat > "$site/anchoring_swipl.pth" <<PTH
import os; os.environ.setdefault("SWI_HOME_DIR", "$swipl_home"); os.environ["PATH"] = "$(dirname "$swipl_bin")" + os.pathsep + os.environ.get("PATH", "")
PTH
ln -sf "$swipl_bin" "$venv/bin/swipl"
"$venv/bin/python" -c "import janus_swi as j; assert j.query_once('X is 1+1')['X'] == 2" \
  || { log "janus-swi does not work"; exit 1; }
log "ready: $venv (swipl $("$swipl_bin" --version | awk '{print $3}'))"
