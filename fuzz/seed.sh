#!/usr/bin/env bash
# Seed each fuzz target's corpus (fuzz/corpus/<target>/, not tracked) from the
# real files in ../shared/data, and from a map file and a map_server YAML that
# covmap writes itself. Run from the repository: bash fuzz/seed.sh
set -euo pipefail
cd "$(dirname "$0")"
data=../../shared/data
for t in carmen sonar_text map_file map_file_entries image ros_map_yaml yaml_nesting geojson aria; do mkdir -p "corpus/$t"; done
if [ -d "$data" ]; then
    for f in "$data"/carmen/*.log.gz; do
        # The gzip file whole, and its first lines as plain text.
        cp -f "$f" corpus/carmen/
        # zcat stops early when head has enough: its broken pipe is no error.
        { zcat "$f" || true; } | head -c 60000 > "corpus/carmen/$(basename "$f" .gz).head"
    done
    { head -c 4000 "$data/sonar-8ring/poses.txt"; printf '\0'; head -c 8000 "$data/sonar-8ring/measurement.txt"; } > corpus/sonar_text/sonar-8ring
    cp -f "$data/worlds/stata_basement.yaml" corpus/ros_map_yaml/
    head -c 20000 "$data/worlds/AMROffice.map" > corpus/aria/AMROffice.head
    head -c 30000 "$data/worlds/willow-full.pgm" > corpus/image/willow.head
    cp -f "$data/worlds/stata_basement.png" corpus/image/
else
    echo "seed.sh: $data is absent: the corpora start from covmap's own files only" >&2
fi
printf 'image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n' > corpus/ros_map_yaml/written.yaml
printf '{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"material":"glass"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}]}' > corpus/geojson/square.geojson
# The nesting target spells its value in "[]{},: \"'a-\n#" (byte b is the
# character b mod 13): "[a, [a]]" and a nest of 70.
printf '\000\011\004\006\000\011\001\001' > corpus/yaml_nesting/list
{ printf '%.0s\000' $(seq 70); printf '%.0s\001' $(seq 70); } > corpus/yaml_nesting/deep
# A map file with a history, as CoverageMap.save writes it (needs covmap in
# the Python of $PYTHON, python3 if unset).
python=${PYTHON:-python3}
"$python" - <<'PY' || echo "seed.sh: covmap is not importable in $python: no map file seed" >&2
import os
import struct
import tempfile

import covmap
m = covmap.CoverageMap(covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(8, 10)), bins=4)
m.track_history(True)
m.integrate((0.3, 0.4, 0.0), [0.5, 0.7], [0.0, 0.3], covmap.LaserModel())
m.save("corpus/map_file/small.npz")
# The entry table target's own map (fuzz_targets/map_file_entries.rs), its
# central directory as the target's 14-byte records: the valid table.
m = covmap.CoverageMap(covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(4, 5)))
m.track_history(True)
m.integrate((0.2, 0.2, 0.0), [0.3], [0.0], covmap.LaserModel())
with tempfile.TemporaryDirectory() as tmp:
    m.save(os.path.join(tmp, "map.npz"))
    data = open(os.path.join(tmp, "map.npz"), "rb").read()
names = ["covmap_version.npy", "grid.npy", "histograms.npy", "history_entropies.npy", "history_counts.npy"]
count, _, at = struct.unpack_from("<HII", data, len(data) - 12)
records = b""
for _ in range(count):
    crc, size = struct.unpack_from("<II", data, at + 16)
    name_len, = struct.unpack_from("<H", data, at + 28)
    offset, = struct.unpack_from("<I", data, at + 42)
    name = data[at + 46:at + 46 + name_len].decode()
    records += bytes([names.index(name), 0]) + struct.pack("<III", offset, size, crc)
    at += 46 + name_len
open("corpus/map_file_entries/valid-table", "wb").write(records)
PY
