#!/usr/bin/env bash
# End to end (issue 7 point 6, issue 6 "imported meshes"; docs/session-format.md): replay the
# bundled logs (sketching, sculpting, deformation) with --save-session, load each session back
# with `planesketch export --strict` (rebuilt model bit-identical to the saved mesh), export in
# every format and read the files back (mesh_io through `planesketch import`, the .glb header by
# hand), refuse bad session files with a message naming the JSON path and no output, and replay
# the sculpting and deformation strokes on an imported base mesh: the same model bit for bit as
# sculpting the reconstruction.
set -euo pipefail
bin="${PLANESKETCH_BINARY:?}"
src="${PLANESKETCH_SOURCE_DIR:?}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

python3 "$src/scripts/make-sculpt-log" "$tmp/sculpt.jsonl"
python3 "$src/scripts/make-deform-log" --sketch-only "$tmp/sketch.jsonl"
demo="$src/assets/logs/demo.jsonl"
deform="$src/assets/logs/deform.jsonl"

# === Save from replay, load and export; the exported model is the replayed one
for name in demo sculpt deform; do
  case $name in demo) log=$demo ;; sculpt) log=$tmp/sculpt.jsonl ;; deform) log=$deform ;; esac
  "$bin" replay "$log" -o "$tmp/$name.obj" --save-session "$tmp/$name.json" -q 2>/dev/null
  [ -f "$tmp/$name.mesh.ply" ] || fail "$name: no mesh saved beside the session"
  "$bin" export "$tmp/$name.json" -o "$tmp/$name.out.obj" --strict --report "$tmp/$name.report.json" 2>/dev/null
  cmp "$tmp/$name.obj" "$tmp/$name.out.obj" || fail "$name: the loaded session's model differs from the replayed one"
  # Saving the loaded session again writes the same document and mesh.
  "$bin" export "$tmp/$name.json" -o "$tmp/$name.again.json" --strict 2>/dev/null
  cmp "$tmp/$name.mesh.ply" "$tmp/$name.again.mesh.ply" || fail "$name: re-saved mesh differs"
  python3 - "$tmp/$name.json" "$tmp/$name.again.json" <<'PY' || fail "$name: re-saved document differs"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
a["mesh"]["path"] = b["mesh"]["path"] = ""
assert a == b
PY
done
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
for name, kinds in [("demo", []), ("sculpt", ["cut", "smooth"]), ("deform", ["stiffness", "deform", "deform", "deform"])]:
    s = json.load(open(f"{d}/{name}.json"))
    r = json.load(open(f"{d}/{name}.report.json"))
    assert s["format"] == "planesketch-session" and s["version"] == 1, s.keys()
    got = [op["kind"] for op in s["ops"]]
    assert got == kinds, (name, got)
    assert r["mesh_checked"] and r["mesh_matches"], r
    assert r["sections"] == len(s["sections"]["curves"]) > 0, r
    print(f"{name}: {r['sections']} sections, {r['ops']} ops, {r['faces']} faces, "
          f"read {r['read_ms']:.1f} ms, rebuild {r['rebuild_ms']:.0f} ms")
PY

# === Every export format, read back with mesh_io (`import` reads it and checks it is a solid)
for ext in obj ply off stl glb; do
  "$bin" export "$tmp/sculpt.json" -o "$tmp/x.$ext" 2>/dev/null
  [ -s "$tmp/x.$ext" ] || fail "no .$ext written"
done
for ext in obj ply off; do
  "$bin" import "$tmp/x.$ext" -o "$tmp/x_$ext.json" 2>/dev/null || fail ".$ext export does not read back as a solid"
  "$bin" export "$tmp/x_$ext.json" -o "$tmp/x_$ext.obj" 2>/dev/null
  cmp "$tmp/x_$ext.obj" "$tmp/sculpt.obj" || fail ".$ext export does not read back to the same model"
done
python3 - "$tmp" <<'PY'
import json, struct, sys
d = sys.argv[1]
faces = json.load(open(f"{d}/sculpt.report.json"))["faces"]
verts = json.load(open(f"{d}/sculpt.report.json"))["vertices"]
b = open(f"{d}/x.glb", "rb").read()
magic, version, length = struct.unpack_from("<4sII", b, 0)
assert magic == b"glTF" and version == 2 and length == len(b), (magic, version, length, len(b))
jlen, jtype = struct.unpack_from("<I4s", b, 12)
assert jtype == b"JSON" and jlen % 4 == 0
g = json.loads(b[20:20 + jlen])
blen, btype = struct.unpack_from("<I4s", b, 20 + jlen)
assert btype == b"BIN\x00" and 28 + jlen + blen == len(b)
prim = g["meshes"][0]["primitives"][0]
assert g["accessors"][prim["attributes"]["POSITION"]]["count"] == verts
assert g["accessors"][prim["indices"]]["count"] == 3 * faces
# STL: binary or ASCII, one facet per face
s = open(f"{d}/x.stl", "rb").read()
n = struct.unpack_from("<I", s, 80)[0] if not s.startswith(b"solid") else s.count(b"facet normal")
assert n == faces, (n, faces)
print("formats ok:", verts, "vertices,", faces, "faces")
PY

# === Bad session files: one line naming the file and the JSON path, exit 1, no output
expect_refused() {  # FILE WORDS
  rm -f "$tmp/bad.obj"
  if "$bin" export "$1" -o "$tmp/bad.obj" 2>"$tmp/err"; then fail "accepted $1"; fi
  grep -qF -- "$2" "$tmp/err" || { cat "$tmp/err"; fail "message for $1 lacks: $2"; }
  [ ! -e "$tmp/bad.obj" ] || fail "output written for $1"
}
head -c 5000 "$tmp/sculpt.json" >"$tmp/truncated.json"
expect_refused "$tmp/truncated.json" "not valid JSON"
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
s = json.load(open(f"{d}/sculpt.json"))
def bad(name, change):
    j = json.loads(json.dumps(s)); change(j); json.dump(j, open(f"{d}/{name}.json", "w"))
bad("kind", lambda j: j["ops"][1].__setitem__("kind", "twist"))
bad("version", lambda j: j.__setitem__("version", 2))
bad("type", lambda j: j["ops"][0]["camera"].__setitem__("fov_y_deg", "wide"))
bad("missing", lambda j: j["sections"]["curves"][2].pop("points"))
PY
expect_refused "$tmp/kind.json" "ops[1].kind: unknown operation kind 'twist'"
expect_refused "$tmp/version.json" "version: unsupported session version 2"
expect_refused "$tmp/type.json" "ops[0].camera.fov_y_deg: must be a number (found a string)"
expect_refused "$tmp/missing.json" "sections.curves[2].points: missing field"
# A saved mesh that no longer matches: a warning, or exit 4 with --strict.
cp "$tmp/demo.json" "$tmp/tampered.json"
python3 - "$tmp" <<'PY'
import sys
d = sys.argv[1]
lines = open(f"{d}/demo.mesh.ply").read().split("\n")
k = lines.index("end_header") + 1
x = lines[k].split()
x[0] = repr(float(x[0]) + 1e-9)
lines[k] = " ".join(x)
open(f"{d}/tampered.mesh.ply", "w").write("\n".join(lines))
PY
cmp -s "$tmp/demo.mesh.ply" "$tmp/tampered.mesh.ply" && fail "the tampering changed nothing"
sed -i 's/"demo.mesh.ply"/"tampered.mesh.ply"/' "$tmp/tampered.json"
"$bin" export "$tmp/tampered.json" -o "$tmp/t.obj" 2>"$tmp/err" || fail "a mesh mismatch refused the load"
grep -q "differs from the saved mesh" "$tmp/err" || { cat "$tmp/err"; fail "mismatch not reported"; }
set +e
"$bin" export "$tmp/tampered.json" -o "$tmp/t2.obj" --strict 2>/dev/null
rc=$?
set -e
[ "$rc" -eq 4 ] || fail "--strict mismatch: exit $rc, expected 4"

# === Imported base: the sketch strokes are refused, the operations apply to the imported mesh
"$bin" replay "$tmp/sculpt.jsonl" -o "$tmp/on_base.obj" --base "$tmp/demo.obj" \
  --save-session "$tmp/base.json" --report "$tmp/base_report.json" -q 2>/dev/null
cmp "$tmp/on_base.obj" "$tmp/sculpt.obj" || fail "sculpting the imported demo mesh differs from sculpting the reconstruction"
"$bin" replay "$tmp/sketch.jsonl" -o "$tmp/sketch.obj" -q 2>/dev/null
"$bin" replay "$deform" -o "$tmp/deform_base.obj" --base "$tmp/sketch.obj" -q 2>/dev/null
cmp "$tmp/deform_base.obj" "$tmp/deform.obj" || fail "deforming the imported mesh differs from deforming the reconstruction"
"$bin" export "$tmp/base.json" -o "$tmp/base_out.obj" --strict 2>/dev/null
cmp "$tmp/base_out.obj" "$tmp/sculpt.obj" || fail "the imported-base session does not load back"
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
s, r = json.load(open(f"{d}/base.json")), json.load(open(f"{d}/base_report.json"))
assert s["base"] is not None and s["sections"]["curves"] == [], "the base is saved, no sections"
assert [op["kind"] for op in s["ops"]] == ["cut", "smooth"], s["ops"]
assert r["refused"] and all("imported mesh" in m["message"] for m in r["refused"]), r["refused"]
print("imported base ok:", len(r["refused"]), "sketch strokes refused")
PY
# A mesh that is not a solid is refused as a base, with the reason.
python3 - "$tmp" <<'PY'
import sys
d = sys.argv[1]
open(f"{d}/open.obj", "w").write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n")
PY
if "$bin" import "$tmp/open.obj" -o "$tmp/open.json" 2>"$tmp/err"; then fail "an open mesh was imported"; fi
grep -q "closed" "$tmp/err" || { cat "$tmp/err"; fail "no reason for the refused import"; }
[ ! -e "$tmp/open.json" ] || fail "session written for a refused import"
echo "session files ok"
