#!/bin/sh
# slurm-acct-demo.sh: the farm scenario of tests/t_farm.sh on a single-node Slurm WITH accounting,
# so that `sacct` answers (docs/farm.md, "Accounting: sacct"; issue 25).
#
#   sh scripts/farm/slurm-acct-demo.sh [BIN]        # as root; BIN holds locus-render (default bin)
#
# Packages (Debian 12): slurmdbd (pulls slurm-wlm-mysql-plugin), mariadb-server, mariadb-client,
# munge, slurmctld, slurmd, slurm-client, python3. Run as root with one missing, the script runs
#   apt-get install -y slurmdbd slurm-wlm-mysql-plugin mariadb-server mariadb-client munge slurmctld slurmd slurm-client python3
# itself; otherwise it prints that line and exits 69. Not part of `make check` (a database
# server and four daemons are too heavy for every run); nothing here touches the system's own
# MariaDB, munge or Slurm: everything lives in one temporary directory, removed at the end
# (KEEP=1 keeps it), on loopback ports picked at start.
#
# What it does, every wait bounded (each daemon under `timeout`, each poll counted):
#  1. MariaDB: mariadb-install-db into TMP/db, mariadbd on 127.0.0.1:PORT (private socket too),
#     the database slurm_acct_db and a user slurm for it.
#  2. munged with a fresh key; slurmdbd (accounting_storage/mysql); `sacctmgr -i add cluster
#     locus`; slurmctld (AccountingStorageType=accounting_storage/slurmdbd, ClusterName=locus,
#     jobacct_gather/linux every second); slurmd, the host as its only node (CPUs=2).
#  3. The farm run: fixtures/scenes/anim-trifocal.scene, frames 0-15 in chunks of 4 (tasks 0-3,
#     at most 2 at once) through scripts/farm/slurm-array.sh; frames 0-1 rendered beforehand;
#     frame 9's name is a directory, so task 2 fails with 74 (as in tests/t_farm.sh); the
#     directory removed, task 2 alone is submitted again; `locus-meta cat` joins the 16 files and
#     the result is compared (cmp) with one `locus-render --frames 16` run.
#  4. Prints `sacct -j JOB --format=JobID,JobName,State,ExitCode,Elapsed,TotalCPU,MaxRSS` for the
#     array job and the rerun, and the wall times of each phase.
# Exit: 0 all as expected; 1 the scenario went wrong (says what); 69 packages missing or not
# root; 70 a daemon did not start (its log's tail is printed).
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${1:-$TOP/bin}
BIN=$(cd "$BIN" 2> /dev/null && pwd) || { echo "slurm-acct-demo: no directory ${1:-$TOP/bin}" >&2; exit 69; }
R="$BIN/locus-render"
M="$BIN/locus-meta"
SCENE="$TOP/fixtures/scenes/anim-trifocal.scene"
PKGS="slurmdbd slurm-wlm-mysql-plugin mariadb-server mariadb-client munge slurmctld slurmd slurm-client python3"
PLUGDIR=/usr/lib/x86_64-linux-gnu/slurm-wlm
[ -d "$PLUGDIR" ] || PLUGDIR=$(dirname "$(ls /usr/lib/*/slurm-wlm/accounting_storage_mysql.so 2> /dev/null | head -1)" 2> /dev/null)

say() { echo "slurm-acct-demo: $*" >&2; }
[ -x "$R" ] && [ -x "$M" ] || { say "build the programs first (make -j2 programs): $R"; exit 69; }
[ "$(id -u)" = 0 ] || { say "needs root (slurmd runs the jobs as their user; the daemons run as root here)"; exit 69; }

missing() {
	for p in mariadb-install-db mariadbd mariadb munged slurmdbd slurmctld slurmd sbatch sacct sacctmgr sinfo python3; do
		command -v $p > /dev/null 2>&1 || { echo $p; return; }
	done
	[ -e "${PLUGDIR:-/nonexistent}/accounting_storage_mysql.so" ] || echo accounting_storage_mysql.so
}
m=$(missing)
if [ -n "$m" ]; then
	say "$m missing: apt-get install -y $PKGS"
	timeout 600 apt-get install -y $PKGS > /dev/null 2>&1 || { say "apt-get failed; run: apt-get install -y $PKGS"; exit 69; }
	m=$(missing)
	[ -z "$m" ] || { say "$m still missing after apt-get"; exit 69; }
fi

S=$(mktemp -d /tmp/slurm-acct.XXXXXX)
chmod 755 "$S"
mkdir -p "$S/db" "$S/state" "$S/spool" "$S/log" "$S/frames"
PIDS=
stop_all() {
	# in reverse start order: slurmd, slurmctld, slurmdbd, mariadbd, munged
	for p in $PIDS; do kill "$p" 2> /dev/null; i=0
		while kill -0 "$p" 2> /dev/null && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
		kill -9 "$p" 2> /dev/null
	done
	PIDS=
	if [ "${KEEP:-0}" = 1 ]; then say "kept $S"; else rm -rf "$S"; fi
}
trap 'stop_all' EXIT
trap 'stop_all; trap - EXIT; exit 130' INT TERM HUP
started() { PIDS="$1 $PIDS"; }
fail() { say "$*"; exit 1; }
dead() { say "$1 did not start:"; tail -5 "$2" >&2; exit 70; }
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }

T0=$(now)
set -- $(python3 -c 'import socket
s=[socket.socket() for i in range(4)]
for x in s: x.bind(("127.0.0.1", 0))
print(" ".join(str(x.getsockname()[1]) for x in s))')
DBPORT=$1 DBDPORT=$2 CTLDPORT=$3 SLURMDPORT=$4
node=$(hostname -s 2> /dev/null || hostname)
PASS=$(od -An -N12 -tx1 /dev/urandom | tr -d ' \n')

# ---- 1. MariaDB ---------------------------------------------------------------------------
timeout 120 mariadb-install-db --no-defaults --user=root --datadir="$S/db" --auth-root-authentication-method=normal \
	--skip-test-db > "$S/log/install-db.log" 2>&1 || dead "mariadb-install-db" "$S/log/install-db.log"
timeout 900 mariadbd --no-defaults --user=root --datadir="$S/db" --socket="$S/mysql.sock" --pid-file="$S/mysql.pid" \
	--port=$DBPORT --bind-address=127.0.0.1 --skip-name-resolve --log-error="$S/log/mariadb.err" \
	--innodb-buffer-pool-size=128M --innodb-log-file-size=64M --innodb-lock-wait-timeout=900 \
	> "$S/log/mariadb.out" 2>&1 &
started $!
sql() { timeout 20 mariadb --no-defaults --socket="$S/mysql.sock" -uroot "$@"; }
i=0; until sql -e 'select 1' > /dev/null 2>&1; do
	i=$((i + 1)); [ $i -lt 60 ] || dead "mariadbd" "$S/log/mariadb.err"; sleep 0.5
done
sql -e "CREATE DATABASE slurm_acct_db; CREATE USER 'slurm'@'127.0.0.1' IDENTIFIED BY '$PASS';
	GRANT ALL ON slurm_acct_db.* TO 'slurm'@'127.0.0.1'; FLUSH PRIVILEGES;" || fail "could not create slurm_acct_db"
T1=$(now)

# ---- 2. munged, slurmdbd, the cluster, slurmctld, slurmd ----------------------------------
dd if=/dev/urandom of="$S/munge.key" bs=1024 count=1 2> /dev/null && chmod 600 "$S/munge.key"
timeout 900 munged -F -f --socket="$S/munge.sock" --key-file="$S/munge.key" --log-file="$S/log/munged.log" \
	--pid-file="$S/munged.pid" --seed-file="$S/munge.seed" --num-threads=4 > "$S/log/munged.out" 2>&1 &
started $!
i=0; while [ ! -S "$S/munge.sock" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
[ -S "$S/munge.sock" ] || dead "munged" "$S/log/munged.out"

cat > "$S/slurmdbd.conf" <<EOF
DbdHost=$node
DbdAddr=127.0.0.1
DbdPort=$DBDPORT
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$S/munge.sock
PidFile=$S/slurmdbd.pid
LogFile=$S/log/slurmdbd.log
StorageType=accounting_storage/mysql
StorageHost=127.0.0.1
StoragePort=$DBPORT
StorageUser=slurm
StoragePass=$PASS
StorageLoc=slurm_acct_db
EOF
chmod 600 "$S/slurmdbd.conf"
cat > "$S/slurm.conf" <<EOF
ClusterName=locus
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$CTLDPORT
SlurmdPort=$SLURMDPORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$S/munge.sock
CredType=cred/munge
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
SlurmctldLogFile=$S/log/slurmctld.log
SlurmdLogFile=$S/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/linux
JobAcctGatherFrequency=1
AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=127.0.0.1
AccountingStoragePort=$DBDPORT
AccountingStoragePass=$S/munge.sock
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
PlugStackConfig=$S/plugstack.conf
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN
PartitionName=farm Nodes=$node Default=YES MaxTime=10 State=UP
EOF
: > "$S/plugstack.conf"
export SLURM_CONF="$S/slurm.conf"      # slurmdbd finds slurmdbd.conf beside it
# AccountingStoragePass names the munge socket for the slurmdbd connection: without it the
# clients (sacctmgr, sacct) and slurmctld use /run/munge/munge.socket.2, not AuthInfo's

timeout 900 slurmdbd -D > "$S/log/dbd.out" 2>&1 &
started $!
i=0; until timeout 5 sacctmgr -n -P list cluster > /dev/null 2> "$S/log/sacctmgr.err"; do
	i=$((i + 1)); [ $i -lt 60 ] || { cat "$S/log/sacctmgr.err" >&2; dead "slurmdbd" "$S/log/slurmdbd.log"; }; sleep 1
done
timeout 20 sacctmgr -i add cluster locus > "$S/log/sacctmgr.out" 2>&1 || { cat "$S/log/sacctmgr.out" >&2; fail "sacctmgr add cluster"; }
T2=$(now)
timeout 900 slurmctld -D -i > "$S/log/ctld.out" 2>&1 &
started $!
timeout 900 slurmd -D -N "$node" > "$S/log/d.out" 2>&1 &
started $!
i=0; until timeout 5 sinfo -h -o %t 2> /dev/null | grep -q idle; do
	i=$((i + 1)); [ $i -lt 30 ] || dead "the node (slurmd/slurmctld)" "$S/log/slurmctld.log"; sleep 1
done
T3=$(now)
say "up: mariadbd 127.0.0.1:$DBPORT, slurmdbd :$DBDPORT, slurmctld :$CTLDPORT, slurmd :$SLURMDPORT, node $node idle"

# ---- 3. the farm run -----------------------------------------------------------------------
# ACCT_SIZE="W H" renders a copy of the scene at W x H instead of 320 x 240: frames long enough
# (a second or more) for jobacct_gather's one-second samples, hence MaxRSS, to see them
if [ -n "${ACCT_SIZE:-}" ]; then
	sed "s/^  size 320 240\$/  size $ACCT_SIZE/" "$SCENE" > "$S/anim-trifocal.scene"
	grep -q "^  size $ACCT_SIZE\$" "$S/anim-trifocal.scene" || fail "ACCT_SIZE=$ACCT_SIZE: no 'size 320 240' line replaced"
	SCENE="$S/anim-trifocal.scene"
fi
F="$S/frames/f-%04d.meta"
"$R" "$SCENE" --frames 0-1 -o "$F" --quiet || fail "pre-rendering frames 0-1"
mkdir "$S/frames/f-0009.meta"                         # task 2 (frames 8-11) cannot write frame 9
cd "$S"
ta=$(now)
LOCUS_RENDER="$R" timeout 300 sbatch --wait --parsable --array=0-3%2 -o "$S/log/task-%a.log" \
	"$TOP/scripts/farm/slurm-array.sh" "$SCENE" 0-15 4 "$F" > "$S/job1" 2> "$S/sbatch1.err"; rc1=$?
tb=$(now)
job1=$(cut -d';' -f1 < "$S/job1")
[ -n "$job1" ] && [ $rc1 != 0 ] || fail "array job: sbatch exit $rc1 (expected a failed task): $(cat "$S/sbatch1.err")"
rmdir "$S/frames/f-0009.meta"
"$M" cat "$S"/frames/f-*.meta --frames 16 -o "$S/joined.meta" 2> "$S/cat1.err" && fail "cat accepted the set without frame 9"
tc=$(now)
LOCUS_RENDER="$R" timeout 300 sbatch --wait --parsable --array=2 -o "$S/log/rerun-%a.log" \
	"$TOP/scripts/farm/slurm-array.sh" "$SCENE" 0-15 4 "$F" > "$S/job2" 2> "$S/sbatch2.err"; rc2=$?
td=$(now)
cd "$TOP"
job2=$(cut -d';' -f1 < "$S/job2")
[ $rc2 = 0 ] || fail "rerun: sbatch exit $rc2: $(cat "$S/sbatch2.err")"
te=$(now)
"$M" cat "$S"/frames/f-*.meta --frames 16 -o "$S/joined.meta" || fail "cat after the rerun"
tf=$(now)
"$R" "$SCENE" --frames 16 --threads 1 -o "$S/one.meta" --quiet || fail "the one-machine run"
tg=$(now)
cmp "$S/joined.meta" "$S/one.meta" || fail "the joined file differs from the one-machine file"

# ---- 4. what accounting kept ---------------------------------------------------------------
# slurmctld sends job records to slurmdbd as they end; wait (bounded) until both jobs are there
fmt=JobID,JobName,State,ExitCode,Elapsed,TotalCPU,MaxRSS
# (a job whose start record has not arrived yet shows as "allocation" without its task id)
i=0
until timeout 10 sacct -n -P -j "$job1,$job2" -o JobID,JobName,State > "$S/sacct.poll" 2> /dev/null \
	&& [ "$(grep -c -E '^[0-9]+_[0-9]+\|locus-frames\|(COMPLETED|FAILED)$' "$S/sacct.poll")" = 5 ] \
	&& [ "$(grep -c -E '^[0-9]+_[0-9]+\.batch\|batch\|(COMPLETED|FAILED)$' "$S/sacct.poll")" = 5 ]; do
	i=$((i + 1)); [ $i -lt 30 ] || { say "sacct did not show both jobs whole within 30 s:"; cat "$S/sacct.poll" >&2; break; }; sleep 1
done
# what accounting must say: tasks 0, 1, 3 of the array and the rerun COMPLETED 0:0, task 2 FAILED 74:0
timeout 10 sacct -n -X -P -j "$job1,$job2" -o JobID,State,ExitCode > "$S/sacct.x" 2>&1
want=$(printf '%s\n' "${job1}_0|COMPLETED|0:0" "${job1}_1|COMPLETED|0:0" "${job1}_2|FAILED|74:0" "${job1}_3|COMPLETED|0:0" "${job2}_2|COMPLETED|0:0")
[ "$(sort "$S/sacct.x")" = "$(echo "$want" | sort)" ] || { say "sacct does not show what happened:"; cat "$S/sacct.x" >&2; sacct_bad=1; }
cat "$S"/log/task-2.log "$S"/log/rerun-2.log > "$S/tasklogs"
echo "== $(date -u '+%Y-%m-%d %H:%M UTC'), $(sacct -V), $(mariadbd --version | sed 's/ *Ver /: /; s/ for .*//'), host $node"
echo "== array job $job1: sbatch --array=0-3%2 slurm-array.sh anim-trifocal.scene${ACCT_SIZE:+ (size $ACCT_SIZE)} 0-15 4 (frames 0-1 there, frame 9 unwritable)"
timeout 10 sacct -j "$job1" --format=$fmt
echo "== rerun job $job2: sbatch --array=2 (the failed task alone)"
timeout 10 sacct -j "$job2" --format=$fmt
echo "== task 2's logs (the failure, then the rerun)"
sed 's|'"$S"'|TMP|g; s|'"$TOP"'/||g' "$S/tasklogs"
echo "== joined 16 frames: identical to one locus-render --frames 16 run ($(wc -c < "$S/one.meta") bytes)"
# sbatch --wait looks at the job at intervals, so its wall time is rounded up; sacct's Start and
# End (whole seconds) give the array's own span: first task started to last task ended
span() { timeout 10 sacct -n -X -P -j "$1" -o Start,End 2> /dev/null | awk -F'|' '
	{ cmd = "date -d " $1 " +%s"; cmd | getline a; close(cmd); cmd = "date -d " $2 " +%s"; cmd | getline b; close(cmd)
	  if (lo == "" || a < lo) lo = a; if (hi == "" || b > hi) hi = b }
	END { if (lo != "") print hi - lo; else print "?" }'; }
echo "== timings (wall, seconds)"
echo "MariaDB install + start      $(secs "$T0" "$T1")"
echo "munged + slurmdbd + cluster  $(secs "$T1" "$T2")"
echo "slurmctld + slurmd to idle   $(secs "$T2" "$T3")"
echo "array job (sbatch --wait)    $(secs "$ta" "$tb")   (sacct: first start to last end $(span "$job1") s)"
echo "rerun of task 2              $(secs "$tc" "$td")   (sacct: $(span "$job2") s)"
echo "locus-meta cat, 16 frames    $(secs "$te" "$tf")"
echo "one process, --frames 16     $(secs "$tf" "$tg")"
echo "whole script so far          $(secs "$T0" "$tg")"
[ -z "${sacct_bad:-}" ] || exit 1
exit 0
