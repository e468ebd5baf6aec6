#!/usr/bin/env bash
# make demo: the Taylor bar (Wang et al. 2007, section 5.1) from its CAD file to ParaView-ready VTK on N ranks.
#   scripts/demo.sh BUILD_DIR CASE_DIR RANKS
set -euo pipefail
build=${1:-build}; case_dir=${2:-build/demo/taylor_bar}; ranks=${3:-2}
root=$(cd "$(dirname "$0")/.." && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

echo "== rkprep: geometry/taylor_bar/scene.yaml -> $case_dir ($ranks ranks)"
"$build/bin/rkprep" "$root/geometry/taylor_bar/scene.yaml" --ranks "$ranks" --out "$case_dir" --force \
  --set time.output_interval=2e-6
echo "== rksolve on $ranks ranks"
mpirun -np "$ranks" "$build/bin/rksolve" "$case_dir"
echo "== rkpost (VTK, plots, ParaView pictures off-screen, report)"
"$build/bin/rkpost" "$case_dir"
/usr/bin/python3 "$root/scripts/plot_taylor.py" "$case_dir"
"$build/bin/rkpost" "$case_dir" --quiet --no-pictures  # again, so that report.md shows the Taylor results
echo
/usr/bin/python3 "$root/scripts/taylor_metrics.py" "$case_dir"
echo
echo "Results:  $case_dir/vtk/case.pvd   (open in ParaView: paraview $case_dir/vtk/case.pvd)"
echo "Pictures: $case_dir/plots/part_ep_*.png (plastic strain)  $case_dir/plots/part_rank_*.png (ranks)"
echo "          $case_dir/plots/taylor_radius_length.png  $case_dir/plots/energies.png"
echo "Report:   $case_dir/report.md"
echo "Data:     $case_dir/history.csv  $case_dir/solve.json  $case_dir/prep.json"
