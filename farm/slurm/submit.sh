#!/usr/bin/env bash
# Submits a Gauss Stylization animation bake to Slurm: the frames in CHUNKS chunks as one array job
# (bake_chunk.sbatch, one task per chunk), then the merge (merge.sbatch) with --dependency=afterok on it.
# See docs/baking.md, "Slurm".
#
#   bash farm/slurm/submit.sh --blend SHOT.blend --object NAME --frames A-B --chunks N --out NAME.pc2 \
#        --farm-cli <add-on>/bake/farm_cli.py [--blender PATH] [--blender-args "..."] [SBATCH OPTION...]
#
# Paths must be readable by every node (a shared file system). The chunks and the jobs' logs go to
# NAME.pc2.chunks/ beside the output. Prints two lines, "array JOBID" and "merge JOBID".
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
usage() { sed -n '2,12p' "$0" >&2; exit 2; }
blend="" object="" frames="" chunks="" out="" farm_cli="" blender="$(command -v blender || true)" blender_args=""
sbatch_options=()
while [ $# -gt 0 ]; do
  case "$1" in
    --blend) blend="$2"; shift 2 ;;
    --object) object="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --chunks) chunks="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --farm-cli) farm_cli="$2"; shift 2 ;;
    --blender) blender="$2"; shift 2 ;;
    --blender-args) blender_args="$2"; shift 2 ;;
    -h|--help) usage ;;
    *) sbatch_options+=("$1"); shift ;;
  esac
done
for value in "$blend" "$object" "$frames" "$chunks" "$out" "$farm_cli"; do [ -n "$value" ] || usage; done
[ -f "$blend" ] || { echo "submit.sh: no .blend file $blend" >&2; exit 1; }
[ -f "$farm_cli" ] || { echo "submit.sh: no farm_cli.py at $farm_cli (the add-on's bake/farm_cli.py)" >&2; exit 1; }
[ -n "$blender" ] || { echo "submit.sh: no blender on PATH; give --blender" >&2; exit 1; }
[[ "$frames" =~ ^(-?[0-9]+)-(-?[0-9]+)$ ]] || { echo "submit.sh: --frames must be A-B, got $frames" >&2; exit 1; }
first="${BASH_REMATCH[1]}" last="${BASH_REMATCH[2]}"
[ "$last" -ge "$first" ] || { echo "submit.sh: the last frame is before the first" >&2; exit 1; }
[[ "$chunks" =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: --chunks must be a positive number" >&2; exit 1; }
count=$((last - first + 1))
size=$(((count + chunks - 1) / chunks))   # frames per chunk; the last may be shorter
tasks=$(((count + size - 1) / size))      # no empty chunk
out="$(realpath -m "$out")"
chunk_dir="$out.chunks"
mkdir -p "$chunk_dir"
rm -f "$chunk_dir"/chunk_*.pc2  # a chunk of an earlier submission must not join this one
farm_cli="$(realpath "$farm_cli")" blend="$(realpath "$blend")"
export GAUSS_BLENDER="$blender" GAUSS_FARM_CLI="$farm_cli" GAUSS_BLEND="$blend"
export GAUSS_OBJECT="$object" GAUSS_FIRST="$first" GAUSS_LAST="$last" GAUSS_CHUNK="$size"
export GAUSS_CHUNK_DIR="$chunk_dir" GAUSS_OUT="$out" GAUSS_BLENDER_ARGS="$blender_args"
array=$(sbatch --parsable --export=ALL --array="0-$((tasks - 1))" --output="$chunk_dir/bake_%A_%a.log" \
        "${sbatch_options[@]}" "$here/bake_chunk.sbatch")
array="${array%%;*}"
merge=$(sbatch --parsable --export=ALL --dependency="afterok:$array" --kill-on-invalid-dep=yes \
        --output="$chunk_dir/merge_%j.log" "${sbatch_options[@]}" "$here/merge.sbatch")
merge="${merge%%;*}"
echo "array $array"
echo "merge $merge"
