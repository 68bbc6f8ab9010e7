#!/bin/bash
# Counts crossings of grown lines independently of terraweave (GEOS through SpatiaLite SQL in
# ogrinfo), as measured in docs/ornaments.md "Crossings":
#   scripts/count_grown_crossings.sh out/ornaments.gpkg samples/map.gpkg hedges:2 ditches:1
# Each argument after the map is a layer of ornaments.gpkg and its class width (metres). Prints,
# per pair of classes, the footprints (lines buffered by half their width) that overlap; per
# class, those overlapping a road's or river's footprint (its `width` attribute) or an
# `existing` polygon of the map; and lines of one class crossing each other other than end to end.
set -euo pipefail
ornaments=$1 map=$2
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
m=$work/m.gpkg
ogr2ogr -f GPKG "$m" "$ornaments"
for l in roads rivers existing; do ogr2ogr -update -nln $l "$m" "$map" $l; done
q() { ogrinfo -q "$m" -dialect SQLite -sql "$1" | grep -E "= " | sed 's/.*= //'; }
classes=("$@")
grown=0 features=0 within=0
for ((i = 0; i < ${#classes[@]}; i++)); do
  a=${classes[i]%%:*} wa=${classes[i]##*:}
  for ((j = i + 1; j < ${#classes[@]}; j++)); do
    b=${classes[j]%%:*} wb=${classes[j]##*:}
    n=$(q "SELECT count(*) FROM $a x, $b y WHERE ST_Distance(CastToXY(x.geom), CastToXY(y.geom)) < ($wa + $wb) / 2.0")
    echo "$a-$b footprints overlapping: $n"
    grown=$((grown + n))
  done
  for f in roads rivers; do
    n=$(q "SELECT count(*) FROM $a g, $f f WHERE ST_Distance(CastToXY(g.geom), f.geom) < ($wa + f.width) / 2.0")
    echo "$a-$f footprints overlapping: $n"
    features=$((features + n))
  done
  n=$(q "SELECT count(*) FROM $a g, existing e WHERE ST_Distance(CastToXY(g.geom), e.geom) < $wa / 2.0")
  echo "$a-existing overlapping: $n"
  features=$((features + n))
  x="ST_Intersection(CastToXY(p.geom), CastToXY(r.geom))"
  ends() { echo "(ST_Equals($x, ST_StartPoint(CastToXY($1.geom))) OR ST_Equals($x, ST_EndPoint(CastToXY($1.geom))))"; }
  n=$(q "SELECT count(*) FROM $a p, $a r WHERE p.fid < r.fid AND ST_Intersects(CastToXY(p.geom), CastToXY(r.geom)) AND NOT (GeometryType($x) = 'POINT' AND $(ends p) AND $(ends r))")
  echo "$a-$a crossing: $n"
  within=$((within + n))
done
echo "total: $grown grown-grown (footprints), $within in a class (crossing), $features grown-feature"
