#!/usr/bin/env bash
# Assembles .devbin/ (ignored) for a GPU machine that has the CUDA driver but neither canopy's
# libraries nor MPI: the binaries of a CUDA build without the renderer, the non-system shared
# libraries they link, OpenMPI (Debian's, relocated there with OPAL_PREFIX), and the commit they
# were built from (.devbin/commit, which bench/run.sh records where there is no git).
# Usage: scripts/device_bundle.sh [BUILD_DIR]   (default build-dev, configured and built here:
#   cmake -G Ninja -S . -B build-dev -DCANOPY_RENDER=OFF -DCANOPY_PYTHON=OFF -DCANOPY_CHECKS=OFF
#   ninja -C build-dev canopy bench_scale test_cuda bench_resolve bench_detect_cuda bench_stand bench_light)
# On the GPU machine, from the repository root: bash scripts/device_check.sh, bash
# scripts/device_ab.sh ..., or source .devbin/env.sh; mpirun -np 2 ... (docs/testing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-dev}
L=/usr/lib/x86_64-linux-gnu
rm -rf .devbin
mkdir -p .devbin/bin .devbin/lib .devbin/ompi/bin .devbin/ompi/lib/x86_64-linux-gnu/openmpi/lib/openmpi3 .devbin/ompi/share
for b in tools/canopy tools/bench_scale tools/bench_resolve tools/bench_detect_cuda tools/bench_stand tools/bench_light tests/test_cuda; do
  [ -f "$build/$b" ] && cp "$build/$b" .devbin/bin/
done
strip .devbin/bin/*
for f in libfmt.so.9 libyaml-cpp.so.0.7 libgomp.so.1 libmpi.so.40 libmpi_cxx.so.40 libopen-rte.so.40 libopen-pal.so.40 \
         libhwloc.so.15 libevent-2.1.so.7 libevent_core-2.1.so.7 libevent_pthreads-2.1.so.7 libmunge.so.2 \
         libmca_common_ompio.so.41 libmca_common_sm.so.40; do
  cp -L "$L/$f" .devbin/lib/
done
cp -L "$L/pmix2/lib/libpmix.so.2" .devbin/lib/
# The light library's ray caster (Embree and its TBB), where the build has it.
for f in libembree3.so.3 libtbb.so.12 libtbbmalloc.so.2; do
  [ -e "$L/$f" ] && cp -L "$L/$f" .devbin/lib/
done
# OpenMPI's components, less those needing fabrics the GPU machine lacks (UCX, OFI, verbs, PSM).
for f in "$L"/openmpi/lib/openmpi3/*.so; do
  case $(basename "$f") in
    *ucx* | *ofi* | *openib* | *psm* | *monitoring* | mca_atomic_* | mca_memheap_* | mca_scoll_* | mca_sshmem_* | mca_spml_* | \
      mca_reachable_netlink*) ;;
    *) cp "$f" .devbin/ompi/lib/x86_64-linux-gnu/openmpi/lib/openmpi3/ ;;
  esac
done
cp /usr/bin/orterun /usr/bin/orted .devbin/ompi/bin/
cp /usr/bin/orterun .devbin/ompi/bin/mpirun
cp -r /usr/share/openmpi .devbin/ompi/share/
# Libraries past 16 MB (Embree's, 44 MB) travel compressed: the device tool carries 64 MiB at most.
for f in .devbin/lib/*; do
  [ "$(stat -c %s "$f")" -gt 16000000 ] && xz -T0 -6 "$f"
done
cat >.devbin/env.sh <<'ENV'
# Source on the GPU machine from the repository root: the carried OpenMPI, relocated.
D=$PWD/.devbin
for f in "$D"/lib/*.xz; do [ -e "$f" ] && [ ! -e "${f%.xz}" ] && xz -dk "$f"; done
export OPAL_PREFIX=$D/ompi PATH=$D/ompi/bin:$PATH LD_LIBRARY_PATH=$D/lib:${LD_LIBRARY_PATH:-}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_pml=ob1 OMPI_MCA_btl=self,vader,tcp OMPI_MCA_osc=pt2pt,sm,rdma OMPI_MCA_io=ompio
export PMIX_MCA_pcompress_base_silence_warning=1 CANOPY_SOURCE_DIR=$PWD
ENV
c=$(git rev-parse --short=7 HEAD 2>/dev/null || echo unknown)
[ -z "$(git status --porcelain --untracked-files=no -- . ':(exclude)bench/results' 2>/dev/null)" ] || c+=-dirty
echo "$c" > .devbin/commit
du -sh .devbin
