#!/bin/bash
# Equal-time noise of regpath with and without manifold NEE on the demo scene: two seeds per
# configuration (interleaved), MSE between the two renders = twice the variance of one.
# Usage: T=SECONDS bench/mnee_equal_time.sh (from the repository root, after scripts/build.sh).
B=${B:-build/lucerna}; S=${S:-scenes/demo/demo.pbrt}; O=${O:-/tmp/mnee_equal_time}; mkdir -p "$O"
T=${T:-20}
for seed in 1 2; do for m in true false; do
    $B render $S --integrator regpath --mnee $m --seed $seed --time $T --spp 100000 --res 240x160 --threads 2 -q \
       -o $O/m$m-s$seed.exr --stats-json $O/m$m-s$seed.json > $O/m$m-s$seed.log 2>&1
done; done
for m in true false; do
  echo "mnee=$m: $(python3 -c "import json;d=[json.load(open('$O/m$m-s%d.json'%s)) for s in (1,2)];print([(x.get('passes'),x.get('mnee_connections'),x.get('regularized_connections')) for x in d])")"
  $B diff $O/m$m-s1.exr $O/m$m-s2.exr --metric mse
  $B diff $O/m$m-s1.exr $O/m$m-s2.exr --metric mse --crop 150,70,240,130
done
