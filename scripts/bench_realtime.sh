#!/usr/bin/env bash
# The real-time benchmark with its peers: installs what is missing (the quick start's
# packages, plus Debian's libbullet-dev and libmujoco-dev for the peer programs), builds with
# -DFILUM_WITH_PEERS=ON and runs bench_realtime, writing apps/bench/results/realtime/
# (realtime.csv, realtime.png, the printed log). About 15 minutes on 2 cores.
# Arguments are passed to bench_realtime, e.g. --quick or --repetitions 3 --duration 2.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
missing=()
for p in libbullet-dev libmujoco-dev pkg-config; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The peers (Bullet, MuJoCo) are built as they compile with those libraries' headers, without -Werror.
cmake -S "$root" -B "$root/build" -DFILUM_WITH_PEERS=ON -DFILUM_WARNINGS_AS_ERRORS=OFF
cmake --build "$root/build" -j"$(nproc)" --target bench_realtime
out="$root/apps/bench/results/realtime"
mkdir -p "$out"
cd "$root"
./build/apps/bench/bench_realtime --out "$out" --plot "$@" | tee "$out/bench_realtime.log"
