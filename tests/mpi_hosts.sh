#!/usr/bin/env bash
# glint-mpi across three hosts simulated on this machine: network
# namespaces (iproute2), each its own host name and address on a bridge of
# their own, with mpirun starting Open MPI's daemons in them through an
# "rsh agent" that enters the namespace instead of ssh. Ranks on different
# hosts talk over TCP, as on a cluster. It checks that
#  - tiles and frames rendered by ranks on three hosts are byte for byte
#    glint render's, and each host rendered some;
#  - the summary names the hosts.
# SKIPPED (exit 77) without mpirun, or where namespaces cannot be made
# (not root, or a sandbox without them).
#   tests/mpi_hosts.sh GLINT GLINT_MPI SCENES_DIR
set -u
glint=$1
glint_mpi=$2
scenes=$3
skip() {
  echo "mpi_hosts: SKIPPED ($*)"
  exit 77
}
command -v mpirun >/dev/null 2>&1 || skip "mpirun is missing"
command -v ip >/dev/null 2>&1 || skip "ip (iproute2) is missing"
command -v unshare >/dev/null 2>&1 || skip "unshare is missing"
[ "$(id -u)" -eq 0 ] || skip "network namespaces need root"
tag=gm$$ # names of our own: another run's are left alone
hub=${tag}hub
hosts=("${tag}a" "${tag}b" "${tag}c")
work=$(mktemp -d)
cleanup() {
  for ns in "${hosts[@]}" "$hub"; do
    ip netns pids "$ns" 2>/dev/null | xargs -r kill -9 2>/dev/null
    ip netns del "$ns" 2>/dev/null
  done
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "mpi_hosts: FAILED: $*"
  for f in "$work"/*.out "$work"/*.err; do
    [ -s "$f" ] && { echo "--- $f"; tail -30 "$f"; }
  done
  exit 1
}
ip netns add "$hub" 2>/dev/null || skip "cannot make network namespaces here"
ip -n "$hub" link add br0 type bridge || skip "cannot make a bridge here"
ip -n "$hub" link set br0 up
for i in 0 1 2; do
  ns=${hosts[$i]}
  ip netns add "$ns" || skip "cannot make namespace $ns"
  ip link add "v$tag$i" netns "$ns" type veth peer name "p$i" netns "$hub" ||
    skip "cannot make veth pairs here"
  ip -n "$hub" link set "p$i" master br0 up
  ip -n "$ns" link set lo up
  ip -n "$ns" addr add "10.77.0.$((i + 1))/24" dev "v$tag$i"
  ip -n "$ns" link set "v$tag$i" up
done
cd "$work"
# The agent mpirun runs instead of ssh: `agent ADDRESS COMMAND...` runs the
# command in that address's namespace, under that host's name.
cat >agent.sh <<EOF
#!/bin/sh
host=\$1
shift
case "\$host" in
10.77.0.1) ns=${hosts[0]} ;;
10.77.0.2) ns=${hosts[1]} ;;
10.77.0.3) ns=${hosts[2]} ;;
*) echo "agent: unknown host \$host" >&2; exit 1 ;;
esac
exec ip netns exec "\$ns" unshare --uts sh -c "hostname \$ns; \$*"
EOF
chmod +x agent.sh
printf '10.77.0.1 slots=1\n10.77.0.2 slots=1\n10.77.0.3 slots=1\n' >hosts
# mpirun itself runs on the first host.
mpirun_on_hosts() {
  ip netns exec "${hosts[0]}" unshare --uts sh -c "hostname ${hosts[0]}; exec \"\$@\"" sh \
    timeout 120 mpirun --allow-run-as-root --hostfile hosts -np 3 \
    --mca plm_rsh_agent "$work/agent.sh" \
    --mca oob_tcp_if_include 10.77.0.0/24 --mca btl_tcp_if_include 10.77.0.0/24 \
    --mca btl tcp,self "$@"
}
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
# Whether Open MPI itself works across these hosts here (a sandbox may
# allow namespaces but not what mpirun needs in them): a job of `hostname`.
if ! mpirun_on_hosts hostname >preflight.out 2>preflight.err ||
  [ "$(sort -u preflight.out | wc -l)" -ne 3 ]; then
  skip "mpirun cannot run across network namespaces here: $(head -c 300 preflight.err)"
fi

"$glint" render billiard -W 160 -H 120 -d 8 -o ref.png -q || fail "glint render"
# Static schedule: each host is then given tiles however late its rank
# starts (with the dynamic one, a rank whose daemon started last on a busy
# machine could find every tile taken, and this check would fail by chance;
# tests/mpi.sh tests that schedule).
mpirun_on_hosts "$glint_mpi" billiard -W 160 -H 120 -d 8 --tile 16 --schedule static -o tiles.png \
  >tiles.out 2>tiles.err || fail "tiles across hosts: exit status $?"
cmp -s ref.png tiles.png || fail "tiles across hosts: not glint render's image"
for i in 0 1 2; do
  grep -q "^  rank $i (${hosts[$i]}): [1-9][0-9]* tiles" tiles.out ||
    fail "rank $i on ${hosts[$i]} rendered no tiles"
done

anim="$scenes/billiard-flight.json"
"$glint" render "$anim" --frames 1-6 -W 96 -H 72 -s 1 -o ref/f%d.png -q ||
  fail "glint render --frames"
mpirun_on_hosts "$glint_mpi" "$anim" --frames 1-6 -W 96 -H 72 -s 1 \
  -o frames/f%d.png >frames.out 2>frames.err || fail "frames across hosts: exit status $?"
for f in 1 2 3 4 5 6; do
  cmp -s "ref/f$f.png" "frames/f$f.png" || fail "frames across hosts: frame $f differs"
done
cat tiles.out
echo "mpi_hosts: PASSED (3 hosts: ${hosts[*]})"
