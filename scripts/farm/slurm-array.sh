#!/bin/sh
# slurm-array.sh: one chunk of an animation's frames per task of a Slurm job array.
#
#   sbatch --array=0-$((CHUNKS - 1))%8 scripts/farm/slurm-array.sh SCENE LIST K OUT [OPTION...]
#
# Task I renders chunk I of the frame LIST (locus-render --frames syntax: N, A-B, A-BxS, comma
# lists) cut into chunks of K frames, the last one shorter when K does not divide the count, one
# file per frame named by the pattern OUT (frames/f-%04d.meta), each renamed into place whole.
# Frames whose file is there and complete are left alone (--skip-existing), so a rerun of the
# whole array, or of the failed tasks alone (sbatch --array=3,7 ...), renders only what is
# missing. CHUNKS is the chunk count:
#   n=$(locus-render SCENE --frames LIST --list-frames | wc -l); CHUNKS=$(( (n + K - 1) / K ))
# OPTIONs go to locus-render as they are (--time-step 0.04, --binary, --fail-fast). The task's
# exit status is locus-render's (0; 65 bad scene; 74 an output it could not write; ...), which
# Slurm records per task (sacct, scontrol show job). Afterwards join and check the whole:
#   locus-meta cat frames/f-*.meta --frames LIST -o film.meta
# docs/farm.md has the walk-through. Environment: LOCUS_RENDER, the program (default:
# locus-render on PATH); SLURM_CPUS_PER_TASK (from --cpus-per-task) sets its threads.
#SBATCH --job-name=locus-frames
#SBATCH --cpus-per-task=1
#SBATCH --output=locus-frames-%A_%a.log
set -u
if [ $# -lt 4 ]; then
	echo "usage: sbatch --array=0-M%P slurm-array.sh SCENE LIST K OUT [OPTION...]" >&2
	exit 64
fi
if [ -z "${SLURM_ARRAY_TASK_ID:-}" ]; then
	echo "slurm-array.sh: SLURM_ARRAY_TASK_ID is not set: submit with sbatch --array" >&2
	exit 64
fi
scene=$1 list=$2 chunk=$3 out=$4
shift 4
echo "slurm-array.sh: job ${SLURM_ARRAY_JOB_ID:-?} task $SLURM_ARRAY_TASK_ID on $(hostname):" \
	"frames $("${LOCUS_RENDER:-locus-render}" "$scene" --frames "$list" --chunk "$chunk" --list-frames | tr '\n' ' ')" >&2
exec "${LOCUS_RENDER:-locus-render}" "$scene" --frames "$list" --chunk "$chunk" \
	--threads "${SLURM_CPUS_PER_TASK:-1}" --skip-existing -o "$out" "$@"
