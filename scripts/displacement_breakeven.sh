B=/work/wt-disp/build/samples/osd-cull
M=/work/shared/data/characters/bigguy.obj
for T in 1 2 4 8; do
  for K in none full acon con; do
    if [ $K = none ]; then
      $B render $M --level 2 --displacement procedural --displacement-scale 0.64 --tess $T --frames 6 --width 512 --height 512 --out /tmp/disp/be.png > /tmp/disp/be_${T}_$K.txt 2>&1
    else
      $B render $M --level 2 --displacement procedural --displacement-scale 0.64 --displaced-bound $K --displaced-box caf --cull occlusion --tess $T --frames 6 --width 512 --height 512 --out /tmp/disp/be.png > /tmp/disp/be_${T}_$K.txt 2>&1
    fi
  done
done
