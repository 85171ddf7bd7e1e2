#!/usr/bin/env bash
# A one-node SLURM cluster made for the test (its own munged, slurmctld and slurmd, ports and state in a scratch
# folder): a fluid-only scene submitted with sbatch runs its ranks through srun and ends with the snapshots of one
# rank, bit for bit; a job cancelled as a time limit ends it (SIGTERM, then SIGKILL) leaves a run that a second job
# restarts with `cosim run --restart` from its newest checkpoint set, ending as the uninterrupted run; a coupled scene
# with 2 fluid ranks under srun ends with the fluid, solid and interface snapshots of the one-rank run, and so does
# one with 2 fluid and 2 solid ranks (a job of 4 tasks, SOLID_RANKS=2: two srun steps side by side).
# Usage: slurm_one_node.sh BUILD_DIR   (as root; exit 77 where slurm-wlm or munge is not installed)
set -euo pipefail
build="$(cd "$1" && pwd)"
source_dir="$(cd "$(dirname "$0")/../.." && pwd)"
for tool in slurmctld slurmd sbatch srun munged mungekey; do
  command -v "$tool" > /dev/null || PATH="$PATH:/usr/sbin" command -v "$tool" > /dev/null || {
    echo "skipped: $tool is not installed (apt-get install slurm-wlm munge)"
    exit 77
  }
done
export PATH="$PATH:/usr/sbin"
if [ "$(id -u)" != 0 ]; then
  echo "skipped: a SLURM daemon needs root"
  exit 77
fi
work="$(mktemp -d /tmp/cosim_slurm_XXXXXX)"
chmod 711 "$work"
pids=()
finish() {
  local rc=$?
  scancel --quiet --full "--name=cosim_slurm_test" 2> /dev/null || true
  for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done
  wait 2> /dev/null || true
  if [ "$rc" = 0 ]; then rm -rf "$work"; else
    echo "--- kept $work; daemon logs:"
    tail -n 20 "$work"/*.log 2> /dev/null || true
  fi
}
trap finish EXIT

free_port() { /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

# munge with a key and a socket of its own
mungekey --create --keyfile="$work/munge.key" > /dev/null 2>&1
munged --force --socket="$work/munge.sock" --key-file="$work/munge.key" --pid-file="$work/munged.pid" \
  --log-file="$work/munged.log" --seed-file="$work/munge.seed" --foreground > "$work/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [ -S "$work/munge.sock" ] && break; sleep 0.1; done

host="$(hostname)"
# The machine's CPUs (plain nproc follows OMP_NUM_THREADS, which CTest sets to 1), at least 4 for the job of 4 tasks
# (2 fluid and 2 solid ranks): the node claims 4 CPUs on a smaller machine (slurmd takes the configuration's word,
# SlurmdParameters=config_overrides), so that each job step gets CPUs of its own. (--overcommit would not do: the
# job would get one CPU, the fluid's step would take it, and the solid's step would wait for it.)
cpus="$(nproc --all)"
[ "$cpus" -ge 4 ] || cpus=4
mkdir -p "$work/state" "$work/spool"
cat > "$work/slurm.conf" << CONF
ClusterName=cosimtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
AuthInfo=socket=$work/munge.sock
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=pmix
KillWait=5
ReturnToService=2
SlurmdParameters=config_overrides
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=4000 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP OverSubscribe=FORCE:4
CONF
export SLURM_CONF="$work/slurm.conf"
slurmctld -D -i -f "$SLURM_CONF" > "$work/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" > "$work/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  [ "$(sinfo -h -o %T 2> /dev/null | head -n 1)" = idle ] && break
  sleep 0.2
done
[ "$(sinfo -h -o %T | head -n 1)" = idle ] || { echo "FAIL: the test cluster's node did not come up"; exit 1; }

cosim="$build/bin/cosim"
scene="$source_dir/configs/sod.yaml"
sets="--set fluid.mesh.cells=[2000] --set fluid.output.interval=0.05 --set fluid.checkpoint.interval=0.02 --set fluid.checkpoint.keep=3"
ok=1
fail() { echo "FAIL: $*"; ok=0; }

# 1. The reference: one rank, no SLURM.
env -u SLURM_JOB_ID "$cosim" run "$scene" --quiet --out "$work/one" $sets > "$work/one.log" 2>&1 ||
  { cat "$work/one.log"; fail "the one-rank run failed"; }

# The example job script of docs/cluster.md, on one node with two tasks of one CPU each.
job_script="$source_dir/examples/cluster/cosim_job.sbatch"
submit() {  # submit RUN OUTPUT [sbatch options] -- [cosim run arguments]
  local run="$1" output="$2"
  shift 2
  local opts=()
  while [ "$1" != -- ]; do opts+=("$1"); shift; done
  shift
  # A job that cannot start fails the test in 5 minutes, never waits for ever.
  local tasks="${job_tasks:-2}"
  timeout 300 sbatch --job-name=cosim_slurm_test --nodes=1 --ntasks="$tasks" --ntasks-per-node="$tasks" --cpus-per-task=1 \
    --output="$output" \
    --export="ALL,SCENE=${job_scene:-$scene},RUN=$run,COSIM=$cosim,SOLID_RANKS=${job_solid_ranks:-1}" "${opts[@]}" \
    "$job_script" "$@"
}

# 2. A batch job of two tasks: cosim starts the fluid's ranks with srun.
submit "$work/two" "$work/job2.out" --wait -- $sets > /dev/null || { cat "$work/job2.out"; fail "the batch job of two ranks failed"; }
grep -q '"srun"' "$work/two/launch.json" || fail "launch.json does not start the fluid with srun: $(cat "$work/two/launch.json")"
ranks="$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["parallel"]["ranks"])' "$work/two/fluid/summary.json")"
[ "$ranks" = 2 ] || fail "the fluid's summary says $ranks ranks, expected 2"
/usr/bin/python3 "$source_dir/tests/cluster/same_snapshots.py" "$work/one/fluid" "$work/two/fluid" || fail "2 ranks under srun differ from one rank"

# 3. A job that runs out of its time: cancelled after its second checkpoint set as the time limit would end it
#    (SIGTERM, SIGKILL after KillWait); the same job script submitted again goes on from the newest set.
long="$sets --set fluid.mesh.cells=[10000] --set fluid.time.end=0.5"  # some 5 s on two idle cores
job="$(submit "$work/three" "$work/job3.out" --parsable -- $long)"
for _ in $(seq 600); do
  [ "$(ls -d "$work/three/checkpoints/"*/ 2> /dev/null | wc -l)" -ge 2 ] && break
  sleep 0.1
done
scancel "$job"
for _ in $(seq 300); do
  squeue -h -j "$job" 2> /dev/null | grep -q . || break
  sleep 0.1
done
status="$(/usr/bin/python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print(s["status"], "|", s.get("reason", ""))' "$work/three/run_summary.json")"
case "$status" in
  interrupted* | failed*) echo "cancelled job: $status" ;;
  *) fail "the cancelled run's summary says: $status" ;;
esac
submit "$work/three" "$work/job4.out" --wait -- $long > /dev/null || { cat "$work/job4.out"; fail "the resubmitted job failed"; }
grep -q "restarting from the checkpoint" "$work/job4.out" || fail "the resubmitted job did not restart: $(head -n 5 "$work/job4.out")"
env -u SLURM_JOB_ID "$cosim" run "$scene" --quiet --out "$work/whole" $long > "$work/whole.log" 2>&1 ||
  fail "the uninterrupted run failed"
/usr/bin/python3 "$source_dir/tests/cluster/same_snapshots.py" "$work/whole/fluid" "$work/three/fluid" ||
  fail "the job restarted after its time limit differs from the uninterrupted run"

# 4. A coupled run (the piston) in a batch job of two tasks: the fluid's two ranks through srun, the solid and the
#    coupler beside them; the fluid, solid and interface snapshots equal the one-rank run's without SLURM.
coupled="$source_dir/configs/piston_2d.yaml"
csets="--set coupling.time.end=0.02 --set coupling.output.interval=0.005"
env -u SLURM_JOB_ID "$cosim" run "$coupled" --quiet --out "$work/coupled_one" $csets > "$work/coupled_one.log" 2>&1 ||
  fail "the coupled one-rank run failed: $(tail -n 5 "$work/coupled_one.log")"
job_scene="$coupled" submit "$work/coupled_two" "$work/job5.out" --wait -- $csets > /dev/null ||
  { cat "$work/job5.out"; fail "the coupled batch job of two fluid ranks failed"; }
grep -q '"srun"' "$work/coupled_two/launch.json" || fail "the coupled job does not start the fluid with srun"
ranks="$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["parallel"]["ranks"])' "$work/coupled_two/fluid/summary.json")"
[ "$ranks" = 2 ] || fail "the coupled fluid's summary says $ranks ranks, expected 2"
for part in fluid solid coupler; do
  /usr/bin/python3 "$source_dir/tests/cluster/same_snapshots.py" "$work/coupled_one/$part" "$work/coupled_two/$part" ||
    fail "the coupled job's $part snapshots differ from the one-rank run's"
done

# 5. The same coupled run in a job of four tasks with SOLID_RANKS=2: the fluid's two ranks and the solid's two ranks
#    in two srun steps; the snapshots again equal the one-rank run's, and the solid's summary has its two METIS parts.
job_tasks=4 job_solid_ranks=2 job_scene="$coupled" submit "$work/coupled_solid" "$work/job6.out" --wait -- $csets > /dev/null ||
  { cat "$work/job6.out"; fail "the coupled batch job of 2 fluid and 2 solid ranks failed"; }
/usr/bin/python3 - "$work/coupled_solid" << 'PY' || fail "the job with solid ranks did not run them under srun"
import json, sys
run = sys.argv[1]
launch = json.load(open(run + "/launch.json"))["commands"]
fluid = json.load(open(run + "/fluid/summary.json"))["parallel"]
solid = json.load(open(run + "/solid/summary.json"))
par = solid["parallel"]
errors = []
for part in ("fluid", "solid"):
    if launch[part][:3] != ["srun", "--ntasks", "2"]:
        errors.append(f"the {part} starts with {launch[part][:3]}, expected srun --ntasks 2")
if fluid["ranks"] != 2:
    errors.append(f"the fluid's summary says {fluid['ranks']} ranks, expected 2")
if par["ranks"] != 2 or par["layout"] != "metis":
    errors.append(f"the solid's summary says {par['ranks']} ranks ({par['layout']}), expected 2 (metis)")
owned = par["elements_per_rank"]
if len(owned) != 2 or min(owned) <= 0 or sum(owned) != solid["elements"]:
    errors.append(f"the solid's parts own {owned} of {solid['elements']} elements")
for e in errors:
    print(e)
sys.exit(1 if errors else 0)
PY
for part in fluid solid coupler; do
  /usr/bin/python3 "$source_dir/tests/cluster/same_snapshots.py" "$work/coupled_one/$part" "$work/coupled_solid/$part" ||
    fail "the job with solid ranks: its $part snapshots differ from the one-rank run's"
done
cmp -s "$work/coupled_one/coupler/interface_history.csv" "$work/coupled_solid/coupler/interface_history.csv" ||
  fail "the job with solid ranks: its interface history differs from the one-rank run's"

[ "$ok" = 1 ] && echo "one-node SLURM: srun ranks equal one rank, alone and coupled (also on solid ranks); a cancelled job restarts bit for bit"
[ "$ok" = 1 ]
