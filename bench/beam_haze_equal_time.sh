#!/bin/bash
# Equal-time noise of regpath with and without the beam techniques in media (--beam-segments) on
# the hazy laser room: two seeds per configuration; the two configurations of one seed run side by
# side, one thread each, so that machine drift hits both alike. Metric: MSE between the two seeds'
# renders (twice the variance of one), per pixel and of 8x8 block means.
# Usage: T=SECONDS bench/beam_haze_equal_time.sh (from the repository root, after scripts/build.sh).
B=${B:-build/lucerna}; S=${S:-scenes/laser/laser-haze.pbrt}; O=${O:-/tmp/beam_haze_equal_time}; mkdir -p "$O"
T=${T:-20}
for seed in 1 2; do
    for m in true false; do
        $B render $S --beam-segments $m --seed $seed --time $T --spp 100000 --threads 1 -q \
           -o $O/b$m-s$seed.exr > $O/b$m-s$seed.log 2>&1 &
    done
    wait
done
for m in true false; do
    echo "beam-segments=$m: $(tail -qn1 $O/b$m-s1.log $O/b$m-s2.log | cut -d' ' -f1-2 | tr '\n' ' ')"
    $B diff $O/b$m-s1.exr $O/b$m-s2.exr --metric mse
    $B diff $O/b$m-s1.exr $O/b$m-s2.exr --metric mse --block 8
done
