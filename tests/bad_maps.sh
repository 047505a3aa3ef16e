# Broken seamless maps for the bad-input cases of the cli_*.sh scripts
# (sourced, not a test): bad_maps MAP DIR writes, from the OBJ MAP with vt,
#  DIR/flip.obj  the first face's first two corners swap their vt (a
#                flipped UV triangle);
#  DIR/seam.obj  a vt used by a vertex with two UVs moved by 1e-3 (a seam
#                off its transition);
#  DIR/novt.obj  no vt at all.

# edit FILE OUT PYTHON: rewrite the OBJ lines through a python expression
edit() {
  python3 - "$1" "$2" "$3" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
exec(sys.argv[3])
open(sys.argv[2], "w").write("\n".join(lines))
PY
}

bad_maps() {
  edit "$1" "$2/flip.obj" '
i = next(k for k, l in enumerate(lines) if l.startswith("f "))
c = lines[i].split()
a, b = c[1].split("/"), c[2].split("/")
c[1], c[2] = a[0] + "/" + b[1], b[0] + "/" + a[1]
lines[i] = " ".join(c)'
  edit "$1" "$2/seam.obj" '
from collections import defaultdict
uses = defaultdict(set)
for l in lines:
    if l.startswith("f "):
        for c in l.split()[1:]:
            v, t = c.split("/")[:2]
            uses[v].add(t)
v = next(v for v, ts in uses.items() if len(ts) > 1)
t = int(sorted(uses[v])[0])
idx = [k for k, l in enumerate(lines) if l.startswith("vt ")][t - 1]
u, w = lines[idx].split()[1:3]
lines[idx] = "vt %r %s" % (float(u) + 1e-3, w)'
  edit "$1" "$2/novt.obj" '
lines = [l for l in lines if not l.startswith("vt ")]
lines = [("f " + " ".join(c.split("/")[0] for c in l.split()[1:])) if l.startswith("f ") else l for l in lines]'
}
