# Sourced by the device rounds: the environment every round needs on the device machine (the
# packages unpacked by pack.sh, the fetched models, CUDA on PATH, the commit under test) and the
# variables root, out (= $OUT), prefix and base (.device/baseline).
root=$(pwd); out=$OUT
prefix=$root/.device/prefix/usr
export LD_LIBRARY_PATH=$prefix/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
export RTRT_MODEL_DIR=$root/.device/models PATH=/usr/local/cuda/bin:$PATH
export RTRT_COMMIT=$(cat .device/commit)
base=$root/.device/baseline
