# Sourced by deploy/bench/rgmap.sh and deploy/bench/slam.sh: the generated buildings (issue 33) a
# benchmark drives, as NAME=MAP specs.
#   random_building_specs GEN DIR COUNT SEED VARIANTS ONLY
# writes COUNT buildings, seeds SEED on, into DIR with GEN (rgnav_building_gen) and prints one
# spec a line: rand_<seed>=DIR/rand_<seed>.png for VARIANTS holding "plain",
# rand_<seed>_furnished=DIR/rand_<seed>_furnitures.png for "furnished". ONLY (the bench's list of
# names to run; empty: all) leaves out those it does not name, unless it holds "random".
random_building_specs() {
  local gen=$1 dir=$2 count=$3 seed0=$4 variants=" $5 " only=" $6 " k s name
  [ "$count" -gt 0 ] || return 0
  [ "$only" = "  " ] || [[ "$only" == *" random "* || "$only" == *" rand_"* ]] || return 0
  "$gen" --seed "$seed0" --count "$count" --out "$dir" >/dev/null
  for ((k = 0; k < count; ++k)); do
    s=$((seed0 + k))
    for name in "rand_$s=$dir/rand_$s.png" "rand_${s}_furnished=$dir/rand_${s}_furnitures.png"; do
      [[ "${name%%=*}" == *_furnished ]] && { [[ "$variants" == *" furnished "* ]] || continue; }
      [[ "${name%%=*}" != *_furnished ]] && { [[ "$variants" == *" plain "* ]] || continue; }
      [ "$only" = "  " ] || [[ "$only" == *" random "* || "$only" == *" ${name%%=*} "* ]] || continue
      echo "$name"
    done
  done
}
