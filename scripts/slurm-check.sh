#!/bin/bash
# Runs slowlight under a real Slurm on this one machine and checks what docs/distributed.md says
# about Slurm: srun and mpirun-inside-an-allocation renders equal the one-process render byte for
# byte, a killed rank ends the job with an error line, an interrupt (scancel, or Ctrl-C at
# srun --disable-status) saves a checkpoint that --resume continues exactly, bad input and a
# missing MPI plugin are one error line.
#
# Not part of CI. Needs root and Debian's Slurm and MUNGE:
#   apt-get install -y slurmctld slurmd slurm-client munge slurm-wlm-basic-plugins
# It starts munged (unless one answers already), slurmctld and slurmd with a one-node
# configuration in a temporary directory (printed), and stops what it started when it ends.
#
# Usage: scripts/slurm-check.sh [BUILD_DIR]     (default: build; needs slowlight and its MPI plugin)
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
bin=$build/slowlight
scene=$here/samples/cornell_box.json

for c in slurmctld slurmd srun salloc sbatch scancel munged munge mpirun cmp; do
    command -v "$c" >/dev/null || { echo "error: $c not found (see the comment at the top of $0)" >&2; exit 2; }
done
[ "$(id -u)" = 0 ] || { echo "error: run as root (slurmd starts the tasks as their user)" >&2; exit 2; }
[ -x "$bin" ] && [ -f "$build/libslowlight_mpi.so" ] ||
    { echo "error: $build has no slowlight or libslowlight_mpi.so (build them first)" >&2; exit 2; }

work=$(mktemp -d /tmp/slowlight-slurm.XXXXXX)
echo "slurm-check: configuration, logs and renders in $work"
mkdir -p "$work/state" "$work/spool" "$work/log"
started_munged=""
cleanup() {
    for p in "$work/slurmd.pid" "$work/slurmctld.pid"; do
        [ -s "$p" ] && kill "$(cat "$p")" 2>/dev/null
    done
    [ -n "$started_munged" ] && [ -s /run/munge/munged.pid ] && kill "$(cat /run/munge/munged.pid)" 2>/dev/null
    sleep 1
}
trap cleanup EXIT

# The configuration: one node, this machine's cores, no cgroups (works in a container too).
cat > "$work/slurm.conf" <<EOF
ClusterName=slowlight-check
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
NodeName=localhost NodeHostname=$(hostname) CPUs=$(nproc) State=UNKNOWN
PartitionName=check Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf

if ! munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
    mkdir -p /run/munge && chown munge:munge /run/munge
    runuser -u munge -- munged || { echo "error: munged did not start" >&2; exit 1; }
    started_munged=1
fi
slurmctld -f "$SLURM_CONF" && slurmd -f "$SLURM_CONF" -N localhost ||
    { echo "error: slurmctld or slurmd did not start (logs in $work/log)" >&2; exit 1; }
for _ in $(seq 30); do sinfo -h -o %t 2>/dev/null | grep -q idle && break; sleep 1; done
sinfo -h -o %t | grep -q idle || { echo "error: the node never became idle (logs in $work/log)" >&2; exit 1; }
echo "slurm-check: $(srun --version), MPI plugins: $(srun --mpi=list 2>&1 | grep -v 'MPI plugin' | tr -d '\t' | tr '\n' ' ')"

cd "$work"
failures=0
pass() { echo "PASS  $*"; }
fail() { echo "FAIL  $*"; failures=$((failures + 1)); }
# same DIR_A DIR_B: every EXR and the video byte-equal
same() {
    local n=0 f
    for f in "$1"/*.exr; do cmp -s "$f" "$2/$(basename "$f")" || n=$((n + 1)); done
    cmp -s "$1.mp4" "$2.mp4" || n=$((n + 1))
    [ "$n" = 0 ] && [ "$(ls "$1"/*.exr | wc -l)" -ge 2 ]
}
small=(render "$scene" --width 64 --height 48 --frames 8 --passes 4 --photons 20000 --no-progress)

"$bin" "${small[@]}" --exr-dir one -o one.mp4 2>one.err || { echo "error: the one-process render failed" >&2; exit 1; }

timeout 120 srun -n 2 --mpi=pmix "$bin" "${small[@]}" --exr-dir srun2 -o srun2.mp4 2>srun2.err &&
    same one srun2 && grep -q "2 MPI ranks" srun2.err && pass "srun -n 2 --mpi=pmix equals one process" ||
    fail "srun -n 2 --mpi=pmix (see $work/srun2.err)"
timeout 120 srun -n 3 --overcommit --mpi=pmix "$bin" "${small[@]}" --exr-dir srun3 -o srun3.mp4 2>srun3.err &&
    same one srun3 && grep -q "3 MPI ranks" srun3.err && pass "srun -n 3 --overcommit --mpi=pmix equals one process" ||
    fail "srun -n 3 --mpi=pmix (see $work/srun3.err)"
timeout 120 salloc -n 2 mpirun --allow-run-as-root "$bin" "${small[@]}" --exr-dir salloc2 -o salloc2.mp4 \
    2>salloc2.err && same one salloc2 && grep -q "2 MPI ranks" salloc2.err &&
    pass "salloc -n 2 mpirun equals one process" || fail "salloc -n 2 mpirun (see $work/salloc2.err)"
printf "#!/bin/sh\nmpirun --allow-run-as-root %s %s --exr-dir sbatch2 -o sbatch2.mp4\n" "$bin" "${small[*]}" > job.sh
timeout 120 sbatch --wait -n 2 -o sbatch2.err -D "$work" job.sh >/dev/null &&
    same one sbatch2 && grep -q "2 MPI ranks" sbatch2.err && pass "sbatch -n 2 with mpirun inside equals one process" ||
    fail "sbatch -n 2 with mpirun (see $work/sbatch2.err)"

timeout 60 srun -n 2 --mpi=none "$bin" "${small[@]}" -o none.mp4 2>none.err
rc=$?
[ "$rc" = 1 ] && [ "$(grep -c '^error:' none.err)" = 1 ] && [ ! -e none.mp4 ] &&
    pass "srun --mpi=none: exit 1, one error line, nothing written" || fail "srun --mpi=none: exit $rc (see $work/none.err)"

printf '{ "camera": { "position": [0, 1, 3], }\n' > bad.json
timeout 60 srun -n 2 --mpi=pmix "$bin" render bad.json -o bad.mp4 --no-progress 2>bad.err
rc=$?
[ "$rc" = 2 ] && [ "$(grep -c '^error: bad.json' bad.err)" = 1 ] && [ ! -e bad.mp4 ] &&
    pass "bad scene under srun: exit 2, one error line naming the file" || fail "bad scene: exit $rc (see $work/bad.err)"

# A longer render for the faults: a checkpoint after every pass shows when it is under way.
long=(render "$scene" --width 96 --height 64 --frames 16 --passes 60 --photons 100000 --no-progress --threads 1)
# rank_pid K: the slowlight process srun started as task K
rank_pid() {
    local p
    for p in $(pgrep -x slowlight); do
        tr '\0' '\n' </proc/"$p"/environ 2>/dev/null | grep -qx "SLURM_PROCID=$1" && echo "$p"
    done
}
wait_for() { for _ in $(seq 600); do [ -e "$1" ] && return 0; sleep 0.1; done; return 1; }

timeout 120 srun -n 2 --mpi=pmix --kill-on-bad-exit=1 "$bin" "${long[@]}" --checkpoint-every 0 \
    --exr-dir killed -o killed.mp4 2>killed.err &
job=$!
wait_for killed/section_0000.ckpt && kill -9 "$(rank_pid 1)"
wait $job
rc=$?
[ "$rc" != 0 ] && [ "$rc" != 124 ] && grep -q '^error: the MPI launcher stopped this render' killed.err &&
    pass "rank 1 killed (srun --kill-on-bad-exit=1): srun exit $rc, rank 0's error line, no hang" ||
    fail "killed rank: exit $rc (see $work/killed.err)"

timeout 120 srun -n 2 --mpi=pmix --disable-status "$bin" "${long[@]}" --checkpoint-every 0 --exr-dir ctrlc \
    -o ctrlc.mp4 2>ctrlc.err &
job=$!
# srun is timeout's child: the first srun by pid may be an earlier step's, not yet reaped.
wait_for ctrlc/section_0000.ckpt && kill -INT "$(pgrep -P "$job" -x srun)"
wait $job
rc=$?
[ "$rc" = 130 ] && [ -e ctrlc/section_0000.ckpt ] && grep -q 'state saved in' ctrlc.err &&
    pass "Ctrl-C at srun --disable-status: every rank saved and exited 130" ||
    fail "Ctrl-C at srun --disable-status: exit $rc (see $work/ctrlc.err)"

"$bin" "${long[@]}" --exr-dir long -o long.mp4 2>long.err
timeout 120 srun -n 2 --mpi=pmix "$bin" "${long[@]}" --checkpoint-every 0 --exr-dir cut -o cut.mp4 2>cut.err &
job=$!
wait_for cut/section_0000.ckpt && scancel --signal=INT "$(squeue -h -o %i -n slowlight | head -1)"
wait $job
rc=$?
[ "$rc" = 130 ] && [ -e cut/section_0000.ckpt ] && [ "$(grep -c 'interrupted: ending the pass' cut.err)" = 1 ] &&
    pass "scancel --signal=INT: every rank saved and exited 130 (srun exit 130)" ||
    fail "scancel --signal=INT: exit $rc (see $work/cut.err)"
timeout 120 srun -n 3 --overcommit --mpi=pmix "$bin" "${long[@]}" --exr-dir cut -o cut.mp4 --resume 2>resume.err &&
    same long cut && pass "--resume on 3 ranks equals the uninterrupted one-process render" ||
    fail "--resume on 3 ranks (see $work/resume.err)"

echo "slurm-check: $failures failed"
[ "$failures" = 0 ]
