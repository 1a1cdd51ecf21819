#!/bin/bash
# The checks of the device backend on a machine with an NVIDIA GPU, in one go: the device
# tests against the compiled CPU loop on the GPU itself (not the simulator), then
# benchmarks/bench_gpu.py (its table on stdout, its JSON in benchmarks/results/).
#     pip install -e ".[cuda,test]" && bash benchmarks/gpu_checks.sh
set -o pipefail
export NUMBA_ENABLE_CUDASIM=0 PYTHONUNBUFFERED=1
python -c "from numba import cuda; print(cuda.get_current_device().name)" || exit 2
python -m pytest -q -p no:cacheprovider -o addopts="" \
  tests/engine/loops/test_cuda_loop.py tests/engine/loops/test_cuda_plan.py \
  tests/engine/loops/test_cuda_physics.py tests/pipeline/test_sweep_backend.py || exit 1
python benchmarks/bench_gpu.py "$@"
